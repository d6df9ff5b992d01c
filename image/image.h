#pragma once
// Images the renderer produces, and their files: PNG (8-bit; colours through the exact sRGB
// curve, data as they are) and EXR (float, unclamped), through OpenImageIO.
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "image/display.h"
#include "scene/image_io_module.h"  // ImageComparison
#include "scene/srgb.h"             // the PNG encoding

namespace manylight {

// Thrown when an image cannot be written or read.
class ImageError : public Error {
 public:
  using Error::Error;
};

// What an image's RGB values are, which decides how a PNG stores them.
enum class ImageValues {
  Colour,  // linear colour (radiance, base colour): code = sRGB encoding of the value
  Data,    // material data (metallic, roughness, normals): code = 255 · value
};

// Linear RGBA float pixels, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;
  ImageValues values = ImageValues::Colour;
  float* pixel(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

// Writes `image` to `path`: .png as 8-bit RGBA (displayCodes), .exr as float RGBA holding
// the values themselves, colour scaled by 2^exposure (no tone map: EXR stays linear). Creates
// missing parent folders, writes a temporary file beside the target and renames it, so a failure
// leaves no partial file. Throws ImageError.
void writeImage(const Image& image, const std::string& path, const Display& display = {});

// The 8-bit RGBA codes a PNG of `image` holds: `display`'s exposure and tone map, then the
// sRGB curve, for colour (straight, not premultiplied); code = 255 · value for data; alpha
// = 255 · coverage.
std::vector<std::uint8_t> displayCodes(const Image& image, const Display& display);

// Throws ImageError unless `path` names a format writeImage writes (.png, .exr).
void checkOutputPath(const std::string& path);

// Reads an image as float RGBA (8-bit files as their codes / 255, not decoded), and where
// `channels` is given, the file's channel count into it. Throws ImageError.
Image readImage(const std::string& path, int* channels = nullptr);

// `manylight compare`: two image files, value by value against two thresholds, or with
// maxRelative ≥ 0 pixel by pixel against the second as the reference (relativeError of
// image/image_errors.h over the pixels it covers): the percentile-th percentile of the
// pixels' relative errors may be at most maxRelative.
struct CompareThresholds {
  double maxAbs = 0.0;        // a value may differ by this much (8-bit files: codes / 255)
  double maxFraction = 0.0;   // the share of values allowed to differ by more
  double maxRelative = -1.0;  // < 0: value by value
  double percentile = 100.0;  // in (0, 100]
};

// The relative test's figures: the percentile asked for, the largest and where it is, and
// how many pixels the reference covers.
struct RelativeOutcome {
  double atPercentile = 0.0, largest = 0.0;
  int maxX = -1, maxY = -1;
  long long pixels = 0;
};

struct CompareOutcome {
  ImageComparison values;
  bool relative = false;  // the relative test ran (thresholds.maxRelative ≥ 0, same shape)
  RelativeOutcome errors;
  // Same shape, and at most maxFraction of the values beyond maxAbs; or, with maxRelative,
  // the percentile within it.
  bool passed = false;
  bool diffWritten = false;
};

// Compares the files `a` and `b` with OpenImageIO's comparison. When they fail and
// `diffPath` is not empty, writes the difference there through a temporary file, as an 8-bit
// PNG: |a − b| / (2·maxAbs), clamped (values at the threshold show mid-grey; with maxAbs 0,
// one 8-bit code does); under the relative test each pixel's relative error / (2·maxRelative)
// as grey (black where the reference covers nothing). Throws ImageError when a file cannot be
// read or written.
CompareOutcome compareImageFiles(const std::string& a, const std::string& b,
                                 const CompareThresholds& thresholds, const std::string& diffPath);

}  // namespace manylight
