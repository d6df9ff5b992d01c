#pragma once
// What the GL tests share beyond tests/test_support.h: one GL context per process.
#include "gl/context.h"
#include "image/image.h"
#include "scene/scene.h"

namespace manylight::testing {

// The process's GL context (auto backend), created on first use.
gl::Context& context();

// A render compared with the reference: both sum in float, so a pixel may differ by this share
// of itself on top of ε (measured rounding: below 1e-5), and by the shader's absolute floor
// for near-black pixels (kAbsoluteFloor, cuts/tile_cuts.h).
inline constexpr double kFloatSlack = 1e-4;

// The largest channel difference between two frames of one size over the larger of their peaks.
double largestDifference(const Image& a, const Image& b);

// The Cornell-like room with its spot and `extraLights` more (generators/scene_builder.h:
// point, spot, directional, point, …), written as a GLB and loaded as users load it.
Scene cornellWith(int extraLights);

}  // namespace manylight::testing
