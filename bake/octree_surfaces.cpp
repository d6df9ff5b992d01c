#include "bake/octree_surfaces.h"

#include <algorithm>
#include <cmath>

namespace manylight {

namespace {

struct Grid {
  glm::vec3 origin;
  float edge;
  int cells;  // per axis
  float margin;
};

struct Triangle {
  glm::vec3 a, b, c;
  glm::vec3 normal;              // unnormalised; zero for lines, points and slivers
  glm::vec3 lo{0.0f}, hi{0.0f};  // bounding box, grown by the margin
};

// Whether the grown box of cells [lo, hi] (inclusive) meets the triangle's plane.
bool meetsPlane(const Grid& g, const Triangle& t, glm::ivec3 lo, glm::ivec3 hi) {
  if (t.normal == glm::vec3(0.0f)) return true;
  const glm::vec3 boxLo = g.origin + glm::vec3(lo) * g.edge - glm::vec3(g.margin);
  const glm::vec3 boxHi = g.origin + glm::vec3(hi + 1) * g.edge + glm::vec3(g.margin);
  const glm::vec3 centre = 0.5f * (boxLo + boxHi), half = 0.5f * (boxHi - boxLo);
  const float reach = glm::dot(half, glm::abs(t.normal));
  return std::abs(glm::dot(t.normal, centre - t.a)) <= reach * (1.0f + 1e-5f);
}

// Adds the cells in [lo, hi] that meet the triangle, with the part of the triangle's box in
// each, splitting the range in halves along its longest axis while it is large.
void mark(const Grid& g, const Triangle& t, glm::ivec3 lo, glm::ivec3 hi,
          std::vector<SurfaceCell>& keys) {
  if (!meetsPlane(g, t, lo, hi)) return;
  const glm::ivec3 size = hi - lo + 1;
  if ((long long)size.x * size.y * size.z <= 8) {
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          if (!meetsPlane(g, t, {x, y, z}, {x, y, z})) continue;
          const glm::vec3 cellLo = g.origin + glm::vec3(x, y, z) * g.edge;
          keys.push_back({surfaceCellKey(glm::uvec3(x, y, z)), glm::max(cellLo, t.lo),
                          glm::min(cellLo + glm::vec3(g.edge), t.hi)});
        }
    return;
  }
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
  glm::ivec3 midHi = hi, midLo = lo;
  midHi[axis] = lo[axis] + size[axis] / 2 - 1;
  midLo[axis] = midHi[axis] + 1;
  mark(g, t, lo, midHi, keys);
  mark(g, t, midLo, hi, keys);
}

void markPrimitive(const Grid& g, Triangle t, std::vector<SurfaceCell>& keys) {
  const glm::vec3 lo = glm::min(glm::min(t.a, t.b), t.c) - glm::vec3(g.margin);
  const glm::vec3 hi = glm::max(glm::max(t.a, t.b), t.c) + glm::vec3(g.margin);
  t.lo = lo;
  t.hi = hi;
  const glm::vec3 top(float(g.cells - 1));
  const glm::ivec3 cellLo(glm::clamp(glm::floor((lo - g.origin) / g.edge), glm::vec3(0.0f), top));
  const glm::ivec3 cellHi(glm::clamp(glm::floor((hi - g.origin) / g.edge), glm::vec3(0.0f), top));
  if (!std::isfinite(t.normal.x + t.normal.y + t.normal.z)) t.normal = glm::vec3(0.0f);
  // A sliver's normal is too short to trust its plane test.
  if (glm::dot(t.normal, t.normal) < 1e-20f) t.normal = glm::vec3(0.0f);
  mark(g, t, cellLo, cellHi, keys);
}

// Sorts by key and merges the entries of a key into one, the union of their boxes.
void sortUnique(std::vector<SurfaceCell>& cells) {
  std::sort(cells.begin(), cells.end(),
            [](const SurfaceCell& a, const SurfaceCell& b) { return a.key < b.key; });
  std::size_t out = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (out > 0 && cells[out - 1].key == cells[i].key) {
      cells[out - 1].lo = glm::min(cells[out - 1].lo, cells[i].lo);
      cells[out - 1].hi = glm::max(cells[out - 1].hi, cells[i].hi);
    } else {
      cells[out++] = cells[i];
    }
  }
  cells.resize(out);
}

}  // namespace

const SurfaceCell* SurfaceCells::find(int level, glm::uvec3 cell) const {
  const std::vector<SurfaceCell>& cells = levels[std::size_t(level)];
  const std::uint64_t key = surfaceCellKey(cell);
  const auto it = std::lower_bound(cells.begin(), cells.end(), key,
                                   [](const SurfaceCell& c, std::uint64_t k) { return c.key < k; });
  return it != cells.end() && it->key == key ? &*it : nullptr;
}

SurfaceCells surfaceCells(const Scene& scene, glm::vec3 origin, float leafEdge, int levels,
                          float margin) {
  const Grid g{origin, leafEdge, 1 << (levels - 1), margin};
  SurfaceCells cells;
  cells.levels.resize(std::size_t(levels));
  std::vector<SurfaceCell>& deepest = cells.levels.back();
  std::vector<glm::vec3> world;
  for (const MeshInstance& inst : scene.instances) {
    for (const Primitive& prim : scene.meshes[std::size_t(inst.mesh)].primitives) {
      world.resize(prim.positions.size());
      for (std::size_t i = 0; i < world.size(); ++i)
        world[i] = glm::vec3(inst.world * glm::vec4(prim.positions[i], 1.0f));
      const std::size_t step = prim.mode == PrimitiveMode::Triangles ? 3
                               : prim.mode == PrimitiveMode::Lines   ? 2
                                                                     : 1;
      for (std::size_t i = 0; i + step <= prim.indices.size(); i += step) {
        const glm::vec3 a = world[prim.indices[i]];
        const glm::vec3 b = world[prim.indices[i + step / 2]];
        const glm::vec3 c = world[prim.indices[i + step - 1]];
        const glm::vec3 n = step == 3 ? glm::cross(b - a, c - a) : glm::vec3(0.0f);
        markPrimitive(g, {a, b, c, n}, deepest);
      }
      if (deepest.size() > (std::size_t(1) << 22)) sortUnique(deepest);
    }
  }
  sortUnique(deepest);
  for (int level = levels - 2; level >= 0; --level) {
    std::vector<SurfaceCell>& up = cells.levels[std::size_t(level)];
    for (const SurfaceCell& cell : cells.levels[std::size_t(level) + 1]) {
      const glm::uvec3 c(cell.key & 0x1FFFFF, (cell.key >> 21) & 0x1FFFFF, cell.key >> 42);
      up.push_back({surfaceCellKey(c >> 1u), cell.lo, cell.hi});
    }
    sortUnique(up);
  }
  return cells;
}

}  // namespace manylight
