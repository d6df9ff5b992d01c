#include "image/image_errors.h"

#include <algorithm>
#include <cmath>

#include "scene/image_io.h"

namespace manylight {

ImageErrors measureErrors(const Image& image, const Image& reference,
                          const std::vector<bool>& rows) {
  if (image.width != reference.width || image.height != reference.height)
    throw ImageError("cannot compare a " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " image with a " +
                     std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                     " reference");
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
      double peak = 0.0, diff = 0.0;
      for (int ch = 0; ch < 3; ++ch) {
        peak = std::max(peak, double(r[ch]));
        // A NaN channel counts as infinitely wrong, not as equal.
        const double d = std::abs(double(m[ch]) - double(r[ch]));
        diff = std::max(diff, std::isnan(d) ? HUGE_VAL : d);
        codes[0].pixels.push_back(float(encodeSrgb8(m[ch])) / 255.0f);
        codes[1].pixels.push_back(float(encodeSrgb8(r[ch])) / 255.0f);
      }
      e.maxAbsolute = std::max(e.maxAbsolute, diff);
      relative.push_back(diff / std::max(peak, kRelativeErrorFloor));
    }
  }
  if (relative.empty()) return e;
  std::sort(relative.begin(), relative.end());
  e.maxRelative = relative.back();
  e.p99Relative = relative[std::size_t(std::ceil(0.99 * double(relative.size()))) - 1];
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
