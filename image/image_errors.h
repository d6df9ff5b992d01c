#pragma once
// How far a method's image is from the reference image of the same view: the error figures
// of the benchmark sweep and the stability suite (bench/, docs/stability.md).
#include <vector>

#include "image/image.h"

namespace manylight {

// Relative errors divide by the pixel's largest reference channel, but never by less than
// this: a pixel that should be black and is not reads as a large relative error.
inline constexpr double kRelativeErrorFloor = 1e-6;

struct ImageErrors {
  long long pixels = 0;      // pixels compared: covered by geometry, in the rows compared
  long long nonFinite = 0;   // of them, pixels with a NaN or infinite channel in the image
  double maxRelative = 0.0;  // max over pixels of max_c |image − reference| / peak
  double p99Relative = 0.0;  // its 99th percentile
  double maxAbsolute = 0.0;  // max over pixels and channels of |image − reference|, linear
  // On the 8-bit sRGB output (as PNGs are written, colour channels only), from OpenImageIO's
  // ImageBufAlgo::compare over the compared pixels:
  double rmse8 = 0.0;                 // root mean square difference, in codes / 255
  double psnr8 = 0.0;                 // peak signal-to-noise ratio in dB (infinite when equal)
  double offByMoreThanOneCode = 0.0;  // share of pixels with a channel 2 or more codes off
};

// Compares `image` with `reference` (same size) over the pixels the reference covers (alpha
// > 0) and, when `rows` is not empty, only in rows y where rows[y] is true. Throws
// ImageError when the sizes differ or OpenImageIO fails.
ImageErrors measureErrors(const Image& image, const Image& reference,
                          const std::vector<bool>& rows = {});

}  // namespace manylight
