#pragma once
// The light octree's lights before its cells are built: the order of its light texture,
// each ranged light's support, which lights go into the octree, the global list or
// nowhere, and how many list entries a leaf edge would cost. Internal to bake/
// (bake/light_octree.cpp); each step runs on `threads` threads and gives the same result
// on any number of them.
#include <cstdint>
#include <vector>

#include "bake/light_octree.h"
#include "bake/light_support.h"
#include "bake/octree_surfaces.h"

namespace manylight::octree {

// Lights without a range in lightOrder's order, then the ranged ones by the Morton code of
// their positions over the box that holds them.
std::vector<int> octreeOrder(const std::vector<Light>& lights, int threads);

struct Classified {
  std::vector<Support> supports;                 // per slot of the order; range 0 where unranged
  std::vector<std::uint32_t> inOctree;           // slots of the octree's lights, ascending
  Box domain{glm::vec3(0.0f), glm::vec3(0.0f)};  // the geometry bounds met by their supports
  float margin = 0.0f;                           // LightOctree::margin
};

// Sorts the lights in the slots of `o.order` into the octree's, the global list
// (`o.global`, `o.wholeScene`) and the unreached (`o.unreached`), as light_octree.h says.
Classified classify(const std::vector<Light>& lights, const Bounds& geometry, bool dynamic,
                    int threads, LightOctree& o);

// A quarter of the median support radius of the lights in `slots` (octreeLeafEdge's rule).
float quarterMedianRadius(const std::vector<Support>& supports,
                          const std::vector<std::uint32_t>& slots);

// The list entries a build of `o`'s shape over `surfaces` would write, estimated from up to
// about a thousand of the octree's lights spread along the order: each one's count of
// deepest geometry cells its support may overlap, which is its entries where every cell it
// meets is split to the deepest level (as in a dense scene; fewer where nodes stay coarse),
// scaled to all of them.
double estimatedEntries(const LightOctree& o, const SurfaceCells& surfaces,
                        const Classified& lights);

}  // namespace manylight::octree
