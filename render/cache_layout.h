#pragma once
// Constants of `--indirect` that C++ and GLSL share (glsl/variants.cpp writes them
// into every shader's prelude). No GL.
namespace manylight {

// Cells (of the smaller cascade) across a transition band: two, not the document's one, so
// a camera moving a given distance a frame moves the blend half as far.
inline constexpr float kBandCells = 2.0f;
// A texel's near radius (render/near_field.h) is at least this many cells of the cascade
// whose caches receive its light, so the far part is smooth between caches.
inline constexpr float kNearCells = 1.0f;

// The near field's texels lie in one plane when within this × the near grid's cell of it; a
// pixel as close to the plane, or behind it, skips them (NearField::cellPlanes), and the light it
// misses is of this order relative to theirs.
inline constexpr float kPlaneTolerance = 1e-3f;

// The lights' flux target of the map choice (render/rsm_choice.h) is this many texels wide.
inline constexpr int kRsmChoiceWidth = 1024;

}  // namespace manylight
