#pragma once
// `manylight fit-gamma --calibrate`: measures how the renderer turns 8-bit light colours
// into radiance, by rendering single-light probes on the reference path, and fits the
// power law C = A·c^γ to the measurements (bake/colour_fit.h).
#include <vector>

#include "bake/colour_fit.h"
#include "scene/scene.h"

namespace manylight {

struct ColourCalibration {
  std::vector<FitPair> pairs;  // (code, mean radiance of the probe image) per probed code
  PowerFit fit;
  // The fitted curve against the exact sRGB curve over codes 0–255: the fitted radiance of
  // each code, relative to code 255's, encoded back to an 8-bit code; the largest
  // difference from the code itself, and the first code where it occurs.
  int largestCodeDifference = 0;
  int worstCode = 0;
};

// The codes probed by default: those above the sRGB curve's linear segment (codes ≤ 10 are
// linear, which no power law fits; with them, the log–log fit bends to γ ≈ 1.76).
inline constexpr int kFirstCalibrationCode = 11;

// Renders `scene` lit only by its first light (or the default rig's key light when it has
// none) with a grey colour (c, c, c), decoded exactly, for every code c in
// [firstCode, lastCode] (within 1–255), at width×height through the scene's first camera (or
// the thumbnail framing), and fits the mean radiance of the covered pixels. Needs a current
// context. Throws Error when the probe lights nothing or fewer than two codes are asked for,
// gl::GlError on a driver error.
ColourCalibration calibrateColour(const Scene& scene, int firstCode = kFirstCalibrationCode,
                                  int lastCode = 255, int width = 64, int height = 64);

}  // namespace manylight
