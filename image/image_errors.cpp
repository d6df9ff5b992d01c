#include "image/image_errors.h"

#include <algorithm>
#include <cmath>

#include "scene/image_io.h"

namespace manylight {

namespace {

void checkSameSize(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw ImageError("cannot compare a " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " image with a " +
                     std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " reference");
}

}  // namespace

double relativeError(const float* image, const float* reference) {
  double peak = 0.0, diff = 0.0;
  for (int ch = 0; ch < 3; ++ch) {
    peak = std::max(peak, double(reference[ch]));
    const double d = std::abs(double(image[ch]) - double(reference[ch]));
    diff = std::max(diff, std::isnan(d) ? HUGE_VAL : d);
  }
  return diff / std::max(peak, kRelativeErrorFloor);
}

RelativeErrors relativeErrors(const Image& image, const Image& reference) {
  checkSameSize(image, reference);
  RelativeErrors e;
  double largest = -1.0;
  for (int y = 0; y < reference.height; ++y) {
    for (int x = 0; x < reference.width; ++x) {
      if (reference.pixel(x, y)[3] <= 0.0f) continue;  // background
      const double r = relativeError(image.pixel(x, y), reference.pixel(x, y));
      e.sorted.push_back(r);
      if (r > largest) largest = r, e.maxX = x, e.maxY = y;
    }
  }
  std::sort(e.sorted.begin(), e.sorted.end());
  return e;
}

double percentileOf(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = std::ceil(p / 100.0 * double(sorted.size()));
  return sorted[std::size_t(std::clamp(rank, 1.0, double(sorted.size()))) - 1];
}

ImageErrors measureErrors(const Image& image, const Image& reference,
                          const std::vector<bool>& rows) {
  checkSameSize(image, reference);
  ImageErrors e;
  std::vector<double> relative;
  // The compared pixels' 8-bit codes / 255, packed into one row per image for OpenImageIO.
  RawImage<float> codes[2];
  for (RawImage<float>& c : codes) c.channels = 3;
  for (int y = 0; y < reference.height; ++y) {
    if (!rows.empty() && !rows[std::size_t(y)]) continue;
    for (int x = 0; x < reference.width; ++x) {
      const float* r = reference.pixel(x, y);
      const float* m = image.pixel(x, y);
      if (r[3] <= 0.0f) continue;  // background
      ++e.pixels;
      if (!std::isfinite(m[0]) || !std::isfinite(m[1]) || !std::isfinite(m[2])) ++e.nonFinite;
      double diff = 0.0;
      for (int ch = 0; ch < 3; ++ch) {
        const double d = std::abs(double(m[ch]) - double(r[ch]));
        diff = std::max(diff, std::isnan(d) ? HUGE_VAL : d);
        codes[0].pixels.push_back(float(encodeSrgb8(m[ch])) / 255.0f);
        codes[1].pixels.push_back(float(encodeSrgb8(r[ch])) / 255.0f);
      }
      e.maxAbsolute = std::max(e.maxAbsolute, diff);
      relative.push_back(relativeError(m, r));
    }
  }
  if (relative.empty()) return e;
  std::sort(relative.begin(), relative.end());
  e.maxRelative = relative.back();
  e.p99Relative = percentileOf(relative, 99.0);
  for (RawImage<float>& c : codes) {
    c.width = int(relative.size());
    c.height = 1;
  }
  // Codes are k/255: a threshold of 1.5/255 fails differences of 2 codes or more.
  ImageComparison cmp;
  std::string reason;
  if (!imageIo().compareImages(codes[0], codes[1], 1.5 / 255.0, &cmp, &reason))
    throw ImageError("cannot compare images: " + reason);
  e.rmse8 = cmp.rmsError;
  e.psnr8 = cmp.psnr;
  e.offByMoreThanOneCode = double(cmp.failing) / double(e.pixels);
  return e;
}

}  // namespace manylight
