#pragma once
// The boundary between manylight and its image I/O module, libmanylight_imageio.so: the
// only code that links OpenImageIO. OpenImageIO pulls in about 260 shared libraries whose
// loading takes 0.4-0.6 s on this machine. In a module, that cost is paid only by
// processes that read or write an image (not by --help, a bad command line or a rejected
// scene: 0.05 s instead of 0.47 s), and those libraries stay out of the global symbol
// scope that every lazily bound call of Mesa's LLVM searches.
//
// Both sides are built together by this project with one compiler and standard library,
// so C++ types cross the boundary; errors come back as text, never as exceptions.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace manylight {

// Pixels in memory, row 0 at the top, channels interleaved.
template <typename T>
struct RawImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<T> pixels;
};

struct ImageIoApi {
  // Bumped whenever this struct changes; the loader refuses a module built for another.
  static constexpr int kVersion = 2;
  int version;
  // Decodes an encoded image held in memory; `extension` (".png", ".jpg") picks the reader.
  // Refuses, from the header and before decoding, an image wider or taller than
  // `maxDimension` or with more than `maxPixels` pixels.
  bool (*decode8)(const unsigned char* bytes, std::size_t size, const char* extension,
                  std::int64_t maxDimension, std::int64_t maxPixels, RawImage<std::uint8_t>* out,
                  std::string* error);
  // Encodes 8-bit pixels as a PNG in memory.
  bool (*encodePng8)(const RawImage<std::uint8_t>& image, std::vector<unsigned char>* png,
                     std::string* error);
  // Writes 8-bit RGBA already encoded as sRGB codes (a PNG tagged sRGB).
  bool (*writeSrgb8)(const char* path, const RawImage<std::uint8_t>& image, std::string* error);
  // Writes linear float RGBA (an EXR, zip-compressed).
  bool (*writeLinearFloat)(const char* path, const RawImage<float>& image, std::string* error);
  // Reads any image OpenImageIO reads as float channels (8-bit files as code / 255).
  bool (*readFloat)(const char* path, RawImage<float>* out, std::string* error);
};

}  // namespace manylight

// The module's one exported symbol.
extern "C" const manylight::ImageIoApi* manylight_imageio_api();
