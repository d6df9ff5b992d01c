#include "tests/gl_support.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace manylight::testing {

gl::Context& context() {
  static std::unique_ptr<gl::Context> ctx = gl::createContext(gl::Backend::Auto);
  return *ctx;
}

double largestDifference(const Image& a, const Image& b) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    diff = std::max(diff, std::abs(double(a.rgba[i]) - double(b.rgba[i])));
    peak = std::max({peak, double(a.rgba[i]), double(b.rgba[i])});
  }
  return diff / std::max(peak, 1e-30);
}

}  // namespace manylight::testing
