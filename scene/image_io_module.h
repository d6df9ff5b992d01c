#pragma once
// The boundary between manylight and its image I/O module, libmanylight_imageio.so: the
// only code that links OpenImageIO. OpenImageIO pulls in about 260 shared libraries whose
// loading is most of a small render's start-up. In a module, that cost is paid only by
// processes that read or write an image (not by --help, a bad command line or a rejected
// scene), and those libraries stay out of the global symbol
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

// Two image files compared value by value (every channel of every pixel, as floats: 8-bit
// files as code / 255) by OpenImageIO's ImageBufAlgo::compare.
struct ImageComparison {
  int width[2] = {0, 0}, height[2] = {0, 0}, channels[2] = {0, 0};
  bool sameShape = false;  // same width, height and channel count; nothing else is compared
  double maxError = 0.0, meanError = 0.0, rmsError = 0.0, psnr = 0.0;
  int maxX = 0, maxY = 0, maxChannel = 0;  // where the largest difference is
  long long values = 0;                    // channel values compared
  long long failing = 0;                   // of them, off by more than the threshold
};

struct ImageIoApi {
  // Bumped whenever this struct changes; the loader refuses a module built for another.
  static constexpr int kVersion = 4;
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
  // Compares files `a` and `b`; values off by more than `threshold` count as failing. When
  // `diffPath` is not null and the shapes agree, also writes |a − b| · diffScale, clamped,
  // as an 8-bit PNG (colour channels only) there.
  bool (*compareFiles)(const char* a, const char* b, double threshold, const char* diffPath,
                       double diffScale, ImageComparison* out, std::string* error);
  // Compares two images in memory, as compareFiles does.
  bool (*compareImages)(const RawImage<float>& a, const RawImage<float>& b, double threshold,
                        ImageComparison* out, std::string* error);
};

}  // namespace manylight

// The module's one exported symbol.
extern "C" const manylight::ImageIoApi* manylight_imageio_api();
