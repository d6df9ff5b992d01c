#include "scene/srgb.h"

#include <cmath>

namespace manylight {

std::uint8_t encodeSrgb8(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  const double v =
      linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return std::uint8_t(std::lround(v * 255.0));
}

double decodeSrgb8(std::uint8_t code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

}  // namespace manylight
