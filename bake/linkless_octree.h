#pragma once
// The linkless (pointerless) octree: the light octree of bake/light_octree.h stored as one
// perfect spatial hash per level (bake/spatial_hash.h, Lefebvre and Hoppe 2006, in the
// multi-level form of Choi et al. 2009), which a GL 3.3 fragment shader descends by hashing
// its cell at each level (glsl/light_octree.glsl). It holds, as texture buffers:
//
//   nodes    RG32UI, the hash tables of all levels one after another; a node's texel:
//              branch  (0, child mask: bit x + 2y + 4z where that child exists)
//              leaf    (first, kOctreeLeafBit | count): its list is indices[first, first + count)
//   offsets  RGBA16UI, the offset tables of all levels one after another (x, y, z, 0)
//   indices  R32UI, slots of the octree's own light texture (LightOctree::order): the global
//            list (every pixel's) first, then the leaves' lists
//
// The shader looks up only nodes that exist (a parent's mask says which), so the tables hold
// no keys. Levels, origin and leaf edge come as uniforms (LinklessLevel).
#include <cstdint>
#include <vector>

#include "bake/light_octree.h"

namespace manylight {

using layout::kOctreeLeafBit;

struct LinklessLevel {
  glm::ivec3 dims{1};   // the level's hash table extent
  int nodeBase = 0;     // its first texel in `nodes`
  int offsetBase = 0;   // its first texel in `offsets`
  int offsetCount = 1;  // its offset table's entries
  int nodeCount = 0;    // nodes stored (keys)
  int attempts = 1;     // hash constructions tried
};

struct LinklessOctree {
  glm::vec3 origin{0.0f};
  float leafEdge = 1.0f;
  int levels = 1;
  std::vector<LinklessLevel> level;
  std::vector<std::uint32_t> nodes;    // 2 words per texel
  std::vector<std::uint16_t> offsets;  // 4 values per texel
  std::vector<std::uint32_t> indices;  // slots of `order`
  std::vector<int> order;              // LightOctree::order: the lights' texture order
  std::uint32_t globalCount = 0;       // the global list's length
  std::uint32_t maxLeafCount = 0;      // the longest leaf list
  std::vector<int> wholeScene;         // LightOctree::wholeScene
  std::size_t unreached = 0;           // LightOctree::unreached.size()
  std::size_t bytes() const;
};

// An octree's figures for --stats.
struct OctreeSummary {
  bool built = false;
  int levels = 0;
  float leafEdge = 0.0f;
  std::size_t nodes = 0, slots = 0, offsetEntries = 0, indices = 0, bytes = 0;
  std::uint32_t globalCount = 0, maxLeafCount = 0;
  int hashAttempts = 0;  // hash constructions tried, all levels
  std::vector<int> wholeScene;
  std::size_t unreached = 0;
};
OctreeSummary summarise(const LinklessOctree& octree);

// Hashes every level of `octree`. Never throws on a valid octree.
LinklessOctree packLinklessOctree(const LightOctree& octree);

// The slot of the node with cell `key` at `level` in that level's table (its texel is
// nodes[2 · (nodeBase + slot)]).
std::uint32_t linklessSlot(const LinklessOctree& octree, int level, glm::uvec3 key);

// The leaf list at `p`, found as the shader finds it (tests, statistics): indices
// [first, first + count), after the global list.
OctreeList linklessListAt(const LinklessOctree& octree, glm::vec3 p);

}  // namespace manylight
