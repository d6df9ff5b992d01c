#pragma once
// The light octree's bounds and texel layout, shared by bake/ and the shaders (glsl/variants.h
// emits them into layout.glsl); bake/linkless_octree.h documents the texels.
#include <cstdint>

namespace manylight::layout {

// Levels of the octree at most: cells of the deepest level are 2^15 to the root's edge.
inline constexpr int kMaxOctreeLevels = 16;
// The leaf flag in a node texel's second word; the rest of the word is the list's length.
inline constexpr std::uint32_t kOctreeLeafBit = 0x80000000u;
// List entries one lighting pass of the octree method evaluates at a pixel at most: llvmpipe
// ends a shader invocation's loops after 65,535 iterations in all, a quarter of an
// iteration per entry here (the loop is unrolled by four, plus at most three), and the
// descent takes at most kMaxOctreeLevels more. Longer lists continue in further passes.
inline constexpr int kOctreeEntriesPerPass = 4 * 16000;

}  // namespace manylight::layout
