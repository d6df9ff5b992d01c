#pragma once
// Layout of the node texture: the one place that says where each field of a light tree node
// lives. bake/light_tree_pack.cpp writes it; glsl/light_tree.glsl reads it. Change both
// together.
//
// Format: a GL_RGBA32UI texture buffer (usamplerBuffer) read as a flat array of 32-bit
// words. Floats are stored as their bits (read back with uintBitsToFloat), so the
// representative's index is an exact integer at any light count. The trees of
// bake/light_tree.h (directional, point, spot; each optional) lie one after another; tree t
// starts at word base[t] and node i of it at base[t] + wordsPerNode(t)·i. Bases and strides
// are even, so a node starts at word 0 or 2 of a texel, and the shader reads a node with 3
// texel fetches (4 for spot nodes) whichever it is:
//
//   word 0–2  box minimum (point, spot: positions; directional: directions towards the
//             lights, points on the unit sphere)
//   word 3    representative: light texture slot (bake/light_texture_layout.h), as an int;
//             −1 (0xFFFFFFFF) for an empty node, which holds no light
//   word 4–6  internal nodes: box maximum;
//             leaves: the light's colour · intensity, linear RGB, exact (a leaf's box is a
//             point: its maximum is its minimum)
//   word 7    1/(largest range)²; 0 when any light of the node has no range
//   word 8    internal nodes: total intensity Σ colour · intensity (linear RGB) as one
//             compact word (bake/node_colour.h: the coding, its constants and its error);
//             leaves: 0
//   word 9    spot: cos Θ with Θ = min(spread + widest outer cone angle, π);
//             point: 1/(smallest range)², 0 when no light of the node has a range;
//             directional: 0
//   spot trees only:
//   word 10–12  axis of the cone holding the lights' directions (the way they shine)
//   word 13     sin Θ
//
// A point p can receive light from a spot node only if some direction from the box to p is
// within Θ of the axis.
//
// Memory per node: 40 bytes (directional, point) and 56 bytes (spot); with the intensity as
// three floats they would be 48 and 64.
#include <cstdint>
#include <cstring>

namespace manylight::layout {

inline constexpr int kNodeWords = 10;
inline constexpr int kSpotNodeWords = 14;
inline constexpr int kColourWord = 8;  // an internal node's compact intensity

// A float as the word that stores it, and back (here and in the tile cuts' texels).
inline std::uint32_t wordOf(float f) {
  std::uint32_t w;
  std::memcpy(&w, &f, sizeof w);
  return w;
}
inline float floatOf(std::uint32_t w) {
  float f;
  std::memcpy(&f, &w, sizeof f);
  return f;
}

}  // namespace manylight::layout
