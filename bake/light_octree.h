#pragma once
// The light octree of the first design document ("hashed shading"): an octree over the
// space the scene's ranged lights reach, whose leaves list the lights whose support
// overlaps them. A point's leaf lists every light that reaches the point (none missed);
// bake/linkless_octree.h turns it into the hashed form the fragment shader descends.
//
// A light's support is where its contribution can be non-zero: the ball of radius `range`
// around a point light (the window clamp(1 − (d/range)⁴, 0, 1) is 0 from d = range on), and
// that ball cut by the outer cone for a spot light (the cone's smoothstep is 0 outside it).
// Lights with no range, directional lights, and ranged lights whose support holds the whole
// scene are not in the octree: they are the global list, evaluated at every pixel. Lights
// whose support misses the scene's geometry reach no pixel and are left out.
//
// Construction is top-down, and only in the cells the scene's geometry touches (the only
// places a fragment can be; elsewhere nodes are absent): a node keeps the lights of its parent's
// list that overlap it, and is split into eight children while some light's support boundary
// crosses it (a light holding the whole node would hold each child too) and its edge is above the
// leaf edge. That is the octree the document's insertion of single light trees builds (a node is
// split where some light's single tree is split), found without building the single trees. Only
// children with lights exist; the others are empty leaves, marked absent in their parent.
//
// Bounds: the root is the cube over the scene's geometry bounds intersected with the
// lights' supports, plus a border; at most kMaxOctreeLevels levels (the leaf edge grows to
// fit); at most the budget of list entries below (the leaf edge doubles until they fit).
// Memory is independent of the image size.
#include <cstdint>
#include <string>
#include <vector>

#include "bake/octree_layout.h"
#include "scene/scene.h"

namespace manylight {

using layout::kMaxOctreeLevels;
// List entries at most (the light index texture's texels), under llvmpipe's texture buffer
// limit of 2^27 texels and about 512 MiB of index list; and at most kOctreeEntriesPerLight
// per light in the octree (or kMinOctreeBudget), so memory grows with the light count.
inline constexpr std::size_t kMaxOctreeIndices = std::size_t(1) << 27;
inline constexpr std::size_t kOctreeEntriesPerLight = 24;
inline constexpr std::size_t kMinOctreeBudget = std::size_t(1) << 22;

struct OctreeOptions {
  // Edge of the smallest cells; 0: octreeLeafEdge's rule.
  float leafEdge = 0.0f;
  int threads = 0;  // 0: the hardware's
  // For lights that move (bake/octree_update.h): the root covers the whole geometry, every
  // cell geometry touches below a split node exists (with an empty list where no light
  // reaches it), and ranged lights that reach no geometry stay octree lights.
  bool dynamic = false;
};

// The default leaf edge: a quarter of the median support radius of the ranged lights (a
// cell that small adds about 66% to a point's list in the worst case of lights spread
// evenly in space, and less on the scene's surfaces). 0 when no light is ranged.
float octreeLeafEdge(const std::vector<Light>& lights);

struct OctreeNode {
  glm::uvec3 cell{0};            // integer cell coordinate at its level
  std::uint32_t first = 0;       // leaf: its list, indices[first, first + count)
  std::uint32_t count = 0;       // leaf: lights in its list
  std::uint32_t firstChild = 0;  // branch: its children, in octant order, from here on in
                                 // the next level (only those in childMask)
  std::uint8_t childMask = 0;    // branch: bit x + 2y + 4z set where that child exists
  bool leaf = true;
  // The box in its cell that holds the geometry there (bake/octree_surfaces.h; the cell
  // without geometry): what its lights were tested against.
  glm::vec3 lo{0.0f}, hi{0.0f};
};

struct LightOctree {
  glm::vec3 origin{0.0f};  // the root's lowest corner
  float leafEdge = 1.0f;   // edge of a cell at the deepest level (levels − 1)
  int levels = 1;          // level k holds cells of edge leafEdge · 2^(levels − 1 − k)
  std::vector<std::vector<OctreeNode>> nodes;  // per level; level 0 holds the root alone
  // The octree's light texture: the scene index of the light in each slot. Lights without
  // a range first, then the ranged ones along a Morton curve through their positions, so a
  // leaf's lights lie close together in it (a million lights' texture does not fit in a
  // cache; a leaf's reads then share its lines).
  std::vector<int> order;
  std::vector<std::uint32_t> indices;  // the leaves' lists: slots of `order`
  std::vector<std::uint32_t> global;   // slots of lights evaluated at every pixel
  std::vector<int> wholeScene;  // scene indices of ranged lights whose support holds the scene
  std::vector<int> unreached;   // scene indices of ranged lights that reach no geometry
  std::uint32_t maxLeafCount = 0;
  float margin = 0.0f;  // by which the overlap tests are conservative (float rounding)
  float rootEdge() const { return leafEdge * float(1u << (levels - 1)); }
  std::size_t nodeCount() const;
};

// Builds the octree of `lights` over the geometry of `scene`: refined only in the cells its
// primitives touch (bake/octree_surfaces.h). A scene without geometry gets the whole octree of the
// lights' supports, refined everywhere. Never throws on valid lights.
LightOctree buildLightOctree(const std::vector<Light>& lights, const Scene& scene,
                             const OctreeOptions& options = {});

// The leaf list that holds `p`, found by descending `octree` (for tests and statistics).
// A point outside the root gets the nearest leaf, which is exact: no ranged light reaches it.
struct OctreeList {
  std::uint32_t first = 0, count = 0;
};
OctreeList octreeListAt(const LightOctree& octree, glm::vec3 p);

// Whether light `light` can contribute at `p`: inside its support (see above).
bool lightReaches(const Light& light, glm::vec3 p);

}  // namespace manylight
