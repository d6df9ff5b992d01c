#pragma once
// The IEC 61966-2-1 sRGB transfer curve, exact (a linear segment and a 2.4 power), never a
// 2.2 power: a 2.2 power darkens 215 of the 256 codes, by up to 9. Colours enter the
// renderer as 8-bit sRGB codes (textures, light lists) and leave as 8-bit codes (PNG); all
// arithmetic in between is on linear values.
#include <cstdint>

namespace manylight {

// The encoding of a linear value, clamped to [0, 1] and rounded to the nearest 8-bit code.
std::uint8_t encodeSrgb8(double linear);
// The inverse: the linear value of an 8-bit code.
double decodeSrgb8(std::uint8_t code);

}  // namespace manylight
