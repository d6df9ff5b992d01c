#pragma once
// The cells of the light octree's grid that the scene's geometry touches: the only places a
// fragment can be. The octree is refined only there, so its size grows with the scene's
// surface area over the leaf edge squared, not with the volume the lights fill over its cube.
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace manylight {

struct SurfaceCell {
  std::uint64_t key;  // surfaceCellKey
  glm::vec3 lo, hi;   // the box, inside the cell, that holds the geometry it touches
};

struct SurfaceCells {
  // Per octree level, the cells geometry touches, sorted by key.
  std::vector<std::vector<SurfaceCell>> levels;
  // The cell's entry, or null where no geometry touches it.
  const SurfaceCell* find(int level, glm::uvec3 cell) const;
};

inline std::uint64_t surfaceCellKey(glm::uvec3 c) {
  return std::uint64_t(c.x) | (std::uint64_t(c.y) << 21) | (std::uint64_t(c.z) << 42);
}

// The cells, of `levels` levels whose deepest has cells of `leafEdge` from `origin`, that
// each triangle, line and point of `scene` (in world space) touches or comes within
// `margin` of, each with the box its primitives' bounding boxes (grown by `margin`) cover
// inside it. Conservative: a cell is listed when its box, grown by `margin`, meets the
// primitive's bounding box and, for a triangle, its plane; so every fragment's cell is
// listed (with some cells beside a triangle's edges too), and every fragment lies in its
// cell's box: a wall's cells get a thin slab, which is what the octree tests lights against.
SurfaceCells surfaceCells(const Scene& scene, glm::vec3 origin, float leafEdge, int levels,
                          float margin);

}  // namespace manylight
