#include "scene/image_decode.h"

#include <cstring>

#include "base/error.h"
#include "scene/image_io.h"

namespace manylight {

DecodedImage decodeImage(const unsigned char* bytes, std::size_t size, const std::string& what,
                         std::int64_t maxDimension, std::int64_t maxPixels) {
  // OpenImageIO picks the reader from a file extension; choose it from the magic number.
  const char* extension = nullptr;
  if (size >= 8 && std::memcmp(bytes, "\x89PNG", 4) == 0) {
    extension = ".png";
  } else if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    extension = ".jpg";
  } else {
    throw SceneError(what + ": not a PNG or JPEG image");
  }
  RawImage<std::uint8_t> raw;
  std::string error;
  if (!imageIo().decode8(bytes, size, extension, maxDimension, maxPixels, &raw, &error)) {
    throw SceneError(what + ": cannot decode image: " + error);
  }
  const int channels = std::min(raw.channels, 4);
  DecodedImage img;
  img.width = raw.width;
  img.height = raw.height;
  img.rgba.resize(std::size_t(img.width) * img.height * 4);
  for (std::size_t i = 0, n = std::size_t(img.width) * img.height; i < n; ++i) {
    const std::uint8_t* s = &raw.pixels[i * raw.channels];
    std::uint8_t* d = &img.rgba[i * 4];
    if (channels >= 3) {
      d[0] = s[0], d[1] = s[1], d[2] = s[2];
    } else {
      d[0] = d[1] = d[2] = s[0];  // grey or grey + alpha
    }
    d[3] = channels == 4 ? s[3] : channels == 2 ? s[1] : 255;
  }
  return img;
}

}  // namespace manylight
