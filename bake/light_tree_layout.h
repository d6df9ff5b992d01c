#pragma once
// Layout of the node texture: the one place that says where each field of a light tree node
// lives. bake/light_tree_pack.cpp writes it; glsl/light_tree.glsl reads it. Change both
// together.
//
// Format: a GL_RGBA32UI texture buffer (usamplerBuffer). Floats are stored as their bits
// (read back with uintBitsToFloat), so the representative's index is an exact integer at any
// light count. The trees of bake/light_tree.h (directional, point, spot; each optional) lie
// one after another; tree t starts at texel base[t] and node i of it at
// base[t] + texelsPerNode(t)·i:
//
//   texel 0  .xyz  box minimum (point, spot: positions; directional: directions towards
//                  the lights, points on the unit sphere)
//            .w    representative: light texture slot (bake/light_texture_layout.h), as an
//                  int; −1 (0xFFFFFFFF) for an empty node, which holds no light
//   texel 1  .xyz  box maximum
//            .w    1/(largest range)²; 0 when any light of the node has no range
//   texel 2  .rgb  total intensity: Σ colour · intensity, linear RGB
//            .w    spot: cos Θ with Θ = min(spread + widest outer cone angle, π);
//                  point: 1/(smallest range)², 0 when no light of the node has a range;
//                  directional: 0
//   texel 3  (spot trees only)
//            .xyz  axis of the cone holding the lights' directions (the way they shine)
//            .w    sin Θ
//
// A point p can receive light from a spot node only if some direction from the box to p is
// within Θ of the axis.
namespace manylight::layout {

inline constexpr int kNodeTexels = 3;
inline constexpr int kSpotNodeTexels = 4;

}  // namespace manylight::layout
