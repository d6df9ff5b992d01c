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

// A pixel's relative error: max over channels of |image − reference|, divided by its largest
// reference channel or kRelativeErrorFloor, whichever is larger; a NaN channel counts as
// infinitely wrong.
double relativeError(const float* image, const float* reference);

// Every relative error of the pixels `reference` covers (alpha > 0), sorted, and where the
// largest is (−1, −1 when none is covered): `manylight compare --max-relative`.
struct RelativeErrors {
  std::vector<double> sorted;
  int maxX = -1, maxY = -1;
};
RelativeErrors relativeErrors(const Image& image, const Image& reference);

// The p-th percentile (0 < p ≤ 100) of sorted values: the ⌈p/100 · n⌉-th smallest; 0 when
// there are none.
double percentileOf(const std::vector<double>& sorted, double p);

// Compares `image` with `reference` (same size) over the pixels the reference covers (alpha
// > 0) and, when `rows` is not empty, only in rows y where rows[y] is true. Throws
// ImageError when the sizes differ or OpenImageIO fails.
ImageErrors measureErrors(const Image& image, const Image& reference,
                          const std::vector<bool>& rows = {});

}  // namespace manylight
