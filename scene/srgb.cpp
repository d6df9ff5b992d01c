#include "scene/srgb.h"

#include <array>
#include <cmath>
#include <cstring>

namespace manylight {

namespace {

// The curve itself: the linear segment, then the 2.4 power, rounded to the nearest code.
std::uint8_t encodeByCurve(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  const double v =
      linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return std::uint8_t(std::lround(v * 255.0));
}

template <typename To, typename From>
To bitsAs(From from) {
  static_assert(sizeof(To) == sizeof(From));
  To to;
  std::memcpy(&to, &from, sizeof to);
  return to;
}

// A float in [0, 1) lies in bucket (its bits >> kBucketShift): buckets 2⁻⁸ of their values wide,
// narrower than the gap between two codes' boundaries (at least 0.9% of the value, near 1).
constexpr int kBucketShift = 15;
constexpr std::size_t kBuckets = (std::size_t(0x3f800000) >> kBucketShift) + 1;

// The curve's codes found by comparisons, not by a power. Per code c from 1 to 255, `least`
// holds the least double the curve gives c or more, found once by bisection over the bits of
// the doubles in [0, 1] (they order positive doubles as their values do); the curve never
// gives a smaller code to a larger value (its two pieces meet within 2 · 10⁻⁶ of each other at
// code 10.3, far from a boundary). Per bucket, `start` holds a code at or below that of every
// double that rounds to a float in the bucket: one below its least float's.
struct Encoder {
  std::array<double, 256> least;  // least[255]: past 1, never reached
  std::array<std::uint8_t, kBuckets> start;
  Encoder() {
    for (int c = 1; c <= 255; ++c) {
      std::uint64_t below = bitsAs<std::uint64_t>(0.0), at = bitsAs<std::uint64_t>(1.0);
      while (at - below > 1) {
        const std::uint64_t mid = below + (at - below) / 2;
        (encodeByCurve(bitsAs<double>(mid)) >= c ? at : below) = mid;
      }
      least[std::size_t(c - 1)] = bitsAs<double>(at);
    }
    least[255] = 2.0;
    for (std::size_t b = 0; b < kBuckets; ++b) {
      const float lowest = bitsAs<float>(std::uint32_t(b << kBucketShift));
      const std::uint8_t code = encodeByCurve(lowest);
      start[b] = code > 0 ? std::uint8_t(code - 1) : 0;
    }
  }
  std::uint8_t operator()(double linear) const {
    const std::size_t bucket = std::size_t(bitsAs<std::uint32_t>(float(linear)) >> kBucketShift);
    std::size_t code = start[bucket < kBuckets ? bucket : kBuckets - 1];
    while (linear >= least[code]) ++code;
    return std::uint8_t(code);
  }
};

}  // namespace

std::uint8_t encodeSrgb8(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  static const Encoder encode;
  return encode(linear);
}

double decodeSrgb8(std::uint8_t code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

}  // namespace manylight
