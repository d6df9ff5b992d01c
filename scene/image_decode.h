#pragma once
// Decodes an encoded image (PNG, JPEG, ... anything OpenImageIO reads) held in memory.
// Internal to scene/.
#include <cstdint>
#include <string>
#include <vector>

namespace manylight {

struct DecodedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // 8-bit RGBA, row 0 at the top
};

// Throws SceneError naming `what` when the bytes are not an image OpenImageIO can read, or
// when the image's header gives a size over the limits (checked before decoding).
DecodedImage decodeImage(const unsigned char* bytes, std::size_t size, const std::string& what,
                         std::int64_t maxDimension, std::int64_t maxPixels);

}  // namespace manylight
