#include "bake/light_octree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "bake/light_pack.h"
#include "bake/light_support.h"
#include "bake/octree_lights.h"
#include "bake/octree_surfaces.h"
#include "base/parallel.h"

namespace manylight {

namespace {

// Lists this long are split across threads (the nodes above the task level).
constexpr std::size_t kParallelList = 1 << 16;
// A build whose entries, projected from its finished tasks, exceed its budget this many times
// is abandoned at once for a coarser one.
constexpr double kProjectedOverBudget = 1.5;

using octree::Box;
using octree::coneMeetsBox;
using octree::contains;
using octree::grow;
using octree::overlaps;
using octree::Support;
using octree::supportOf;

Box cellBox(const LightOctree& o, int level, glm::uvec3 cell) {
  const float edge = o.leafEdge * float(1u << (o.levels - 1 - level));
  const glm::vec3 lo = o.origin + glm::vec3(cell) * edge;
  return {lo, lo + glm::vec3(edge)};
}

// A subtree's nodes and lists, built on one thread.
struct Part {
  std::vector<std::vector<OctreeNode>> nodes;  // per level of the whole octree
  std::vector<std::uint32_t> indices;
};

struct Build {
  Build(const LightOctree& o, const std::vector<Support>& s, float m, std::atomic<std::size_t>& e,
        std::atomic<bool>& f)
      : octree(o),
        supports(s),
        margin(m),
        entries(e),
        overflow(f),
        children(std::size_t(o.levels) + 1) {}
  const LightOctree& octree;
  const std::vector<Support>& supports;    // per light texture slot
  const SurfaceCells* surfaces = nullptr;  // null: refine everywhere
  float margin;
  std::atomic<std::size_t>& entries;  // list entries written so far, all parts
  std::atomic<bool>& overflow;
  std::size_t budget = kMaxOctreeIndices;  // list entries at most
  bool keepEmpty = false;                  // OctreeOptions::dynamic
  int threads = 1;                         // for the lists of the nodes above the tasks
  // Per level: the lists of the node being split's children (reused down the recursion).
  std::vector<std::array<std::vector<std::uint32_t>, 8>> children;

  // Nodes of this level are not built here but handed out as tasks (−1: none).
  int taskLevel = -1;
  struct Task {
    std::size_t index;
    std::vector<std::uint32_t> list;
  };
  std::vector<Task> tasks;

  // Appends each of the `n` slots at `slots` to the lists of the children in `mask` whose
  // geometry box its support may overlap.
  void sortIntoChildren(const std::uint32_t* slots, std::size_t n, const std::array<Box, 8>& boxes,
                        std::uint8_t mask, int coneDepth,
                        std::array<std::vector<std::uint32_t>, 8>& lists) const {
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t slot = slots[i];
      const Support& sp = supports[slot];
      const float reach = (sp.radius + margin) * (sp.radius + margin);
      for (int c = 0; c < 8; ++c) {
        if (!(mask & (1u << c))) continue;
        const Box& b = boxes[std::size_t(c)];
        const glm::vec3 d = glm::max(glm::max(b.lo - sp.centre, sp.centre - b.hi), glm::vec3(0.0f));
        if (glm::dot(d, d) > reach) continue;
        if (sp.spot && !coneMeetsBox(sp, b, margin, coneDepth)) continue;
        lists[c].push_back(slot);
      }
    }
  }

  // Makes node `index` of `level` in `part` a leaf or a branch from `list`, the slots of
  // its parent's list that overlap it, and builds its children (depth first).
  void node(Part& part, int level, std::size_t index, const std::vector<std::uint32_t>& list) {
    if (overflow.load(std::memory_order_relaxed)) return;
    if (level == taskLevel) {
      tasks.push_back({index, list});
      return;
    }
    const glm::uvec3 cell = part.nodes[level][index].cell;
    const Box box{part.nodes[level][index].lo, part.nodes[level][index].hi};
    bool split = level + 1 < octree.levels;
    if (split) {
      split = std::any_of(list.begin(), list.end(),
                          [&](std::uint32_t s) { return !contains(supports[s], box, margin); });
    }
    if (!split) {
      OctreeNode& n = part.nodes[level][index];
      n.first = std::uint32_t(part.indices.size());
      n.count = std::uint32_t(list.size());
      part.indices.insert(part.indices.end(), list.begin(), list.end());
      if (entries.fetch_add(list.size()) + list.size() > budget) overflow = true;
      return;
    }
    // Children's lists live one level down, so the children's own splits (which write the
    // level below theirs) leave them alone.
    std::array<std::vector<std::uint32_t>, 8>& lists = children[level + 1];
    std::array<Box, 8> boxes;
    std::uint8_t mask = 0;  // the children geometry touches
    for (int c = 0; c < 8; ++c) {
      lists[c].clear();
      const glm::uvec3 childCell = cell * 2u + glm::uvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      boxes[std::size_t(c)] = cellBox(octree, level + 1, childCell);
      if (surfaces) {
        const SurfaceCell* geometry = surfaces->find(level + 1, childCell);
        if (!geometry) continue;
        boxes[std::size_t(c)] = {geometry->lo, geometry->hi};
      }
      mask |= std::uint8_t(1u << c);
    }
    // Cones against half boxes only for the deepest cells, where the lists are final; above,
    // a looser list only costs the children's tests.
    const int coneDepth = level + 2 == octree.levels ? 1 : 0;
    if (list.size() < kParallelList || threads <= 1) {
      sortIntoChildren(list.data(), list.size(), boxes, mask, coneDepth, lists);
    } else {
      // The top nodes' lists hold most lights: split them in chunks on every thread, joined
      // in order so each child's list stays sorted.
      std::vector<std::array<std::vector<std::uint32_t>, 8>> parts(
          static_cast<std::size_t>(threads));
      const std::size_t chunk = (list.size() + std::size_t(threads) - 1) / std::size_t(threads);
      runOnThreads(threads, [&](int t) {
        const std::size_t begin = std::min(list.size(), chunk * std::size_t(t));
        const std::size_t n = std::min(chunk, list.size() - begin);
        sortIntoChildren(list.data() + begin, n, boxes, mask, coneDepth, parts[std::size_t(t)]);
      });
      for (int c = 0; c < 8; ++c) {
        for (const auto& part : parts)
          lists[c].insert(lists[c].end(), part[c].begin(), part[c].end());
      }
    }
    for (int c = 0; c < 8; ++c) {
      if (lists[c].empty() && !keepEmpty) mask &= std::uint8_t(~(1u << c));
    }
    std::vector<OctreeNode>& next = part.nodes[level + 1];
    const std::uint32_t firstChild = std::uint32_t(next.size());
    for (int c = 0; c < 8; ++c) {
      if (!(mask & (1u << c))) continue;
      OctreeNode child;
      child.cell = cell * 2u + glm::uvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      child.lo = boxes[std::size_t(c)].lo;
      child.hi = boxes[std::size_t(c)].hi;
      next.push_back(child);
    }
    OctreeNode& n = part.nodes[level][index];
    n.leaf = false;
    n.childMask = mask;
    n.firstChild = firstChild;
    std::size_t child = firstChild;
    for (int c = 0; c < 8; ++c) {
      if (mask & (1u << c)) node(part, level + 1, child++, lists[c]);
    }
  }
};

}  // namespace

namespace {

// Builds the subtrees below the task level on `threads` threads and splices them into
// `main`, whose task-level nodes are their roots.
void buildTasks(Build& top, Part& main, int threads) {
  const int levels = top.octree.levels;
  std::vector<Part> parts(top.tasks.size());
  std::atomic<std::size_t> next{0};
  // The entries of the first tasks, once all of them are done, projected over every task by
  // the lengths of their lists: a build that will plainly exceed its budget stops early
  // rather than at the budget. Checked at fixed numbers of tasks (8, 16, 32, …) from their
  // own entries alone, so the decision does not depend on the threads' timing.
  std::vector<double> weightBefore(top.tasks.size() + 1, 0.0);
  for (std::size_t t = 0; t < top.tasks.size(); ++t)
    weightBefore[t + 1] = weightBefore[t] + double(top.tasks[t].list.size());
  std::vector<std::atomic<bool>> finished(top.tasks.size());
  std::mutex prefixMutex;
  std::size_t prefix = 0;  // tasks [0, prefix) are finished
  auto finish = [&](std::size_t t) {
    finished[t] = true;
    const std::lock_guard<std::mutex> lock(prefixMutex);
    while (prefix < finished.size() && finished[prefix]) {
      ++prefix;
      if (prefix < 8 || (prefix & (prefix - 1)) != 0) continue;
      double entries = 0.0;
      for (std::size_t k = 0; k < prefix; ++k) entries += double(parts[k].indices.size());
      if (entries * weightBefore.back() >
          kProjectedOverBudget * double(top.budget) * weightBefore[prefix])
        top.overflow = true;
    }
  };
  runOnThreads(threads, [&](int) {
    Build build(top.octree, top.supports, top.margin, top.entries, top.overflow);
    build.surfaces = top.surfaces;
    build.budget = top.budget;
    build.keepEmpty = top.keepEmpty;
    for (std::size_t t; (t = next.fetch_add(1)) < top.tasks.size();) {
      Part& part = parts[t];
      part.nodes.resize(std::size_t(levels));
      part.nodes[top.taskLevel].push_back(main.nodes[top.taskLevel][top.tasks[t].index]);
      build.node(part, top.taskLevel, 0, top.tasks[t].list);
      finish(t);
    }
  });

  for (std::size_t t = 0; t < parts.size(); ++t) {
    const std::uint32_t indexBase = std::uint32_t(main.indices.size());
    std::vector<std::uint32_t> base(std::size_t(levels) + 1, 0);
    for (int level = 0; level < levels; ++level)
      base[level] = std::uint32_t(main.nodes[level].size());
    for (int level = top.taskLevel; level < levels; ++level) {
      for (OctreeNode n : parts[t].nodes[level]) {
        if (n.leaf) {
          n.first += indexBase;
        } else {
          n.firstChild += base[level + 1];
        }
        if (level == top.taskLevel) {
          main.nodes[level][top.tasks[t].index] = n;
        } else {
          main.nodes[level].push_back(n);
        }
      }
    }
    main.indices.insert(main.indices.end(), parts[t].indices.begin(), parts[t].indices.end());
  }
}

// Sets the levels, leaf edge and origin for a leaf edge of at least `leafEdge`.
void shape(LightOctree& o, const Box& domain, float margin, float leafEdge) {
  const glm::vec3 size = domain.hi - domain.lo;
  const float extent = std::max({size.x, size.y, size.z, 0.0f}) + 4.0f * margin;
  o.levels = 1;
  while (o.levels < kMaxOctreeLevels && leafEdge * float(1u << (o.levels - 1)) < extent) ++o.levels;
  o.leafEdge = std::max(leafEdge, extent / float(1u << (o.levels - 1)));
  o.origin = domain.lo - glm::vec3(2.0f * margin);
}

}  // namespace

float octreeLeafEdge(const std::vector<Light>& lights) {
  std::vector<Support> supports;
  std::vector<std::uint32_t> slots;
  for (const Light& l : lights) {
    if (!isRanged(l)) continue;
    slots.push_back(std::uint32_t(supports.size()));
    supports.push_back(supportOf(l));
  }
  return octree::quarterMedianRadius(supports, slots);
}

std::size_t LightOctree::nodeCount() const {
  std::size_t n = 0;
  for (const auto& level : nodes) n += level.size();
  return n;
}

namespace {

// Builds `o`'s nodes and lists at its shape, refined only in `surfaces` (null: everywhere);
// false, with `o` unchanged, where its lists would exceed `budget` entries.
bool buildShape(LightOctree& o, const octree::Classified& lights, const SurfaceCells* surfaces,
                std::size_t budget, bool dynamic, int threads) {
  std::atomic<std::size_t> entries{0};
  std::atomic<bool> overflow{false};
  Build top(o, lights.supports, lights.margin, entries, overflow);
  // Tasks a few levels down, so that geometry in one corner of the root still makes many.
  top.taskLevel = o.levels > 5 ? 4 : o.levels > 3 ? 2 : -1;
  top.keepEmpty = dynamic;
  top.threads = threads;
  top.budget = budget;
  top.surfaces = surfaces;
  Part main;
  main.nodes.resize(std::size_t(o.levels));
  OctreeNode root;
  const Box rootBox = cellBox(o, 0, glm::uvec3(0));
  root.lo = rootBox.lo;
  root.hi = rootBox.hi;
  const SurfaceCell* geometry = surfaces ? surfaces->find(0, glm::uvec3(0)) : nullptr;
  if (geometry) root.lo = geometry->lo, root.hi = geometry->hi;
  main.nodes[0].push_back(root);
  if (!surfaces || geometry) top.node(main, 0, 0, lights.inOctree);
  if (top.taskLevel >= 0) buildTasks(top, main, threads);
  if (overflow) return false;
  o.nodes = std::move(main.nodes);
  o.indices = std::move(main.indices);
  return true;
}

}  // namespace

LightOctree buildLightOctree(const std::vector<Light>& lights, const Scene& scene,
                             const OctreeOptions& options) {
  LightOctree o;
  const Bounds geometry = scene.bounds();
  const int threads =
      options.threads > 0 ? options.threads : std::max(1, int(std::thread::hardware_concurrency()));
  o.order = octree::octreeOrder(lights, threads);
  const octree::Classified c = octree::classify(lights, geometry, options.dynamic, threads, o);
  o.margin = c.margin;
  float leafEdge = options.leafEdge > 0.0f ? options.leafEdge
                                           : octree::quarterMedianRadius(c.supports, c.inOctree);
  if (!(leafEdge > 0.0f)) leafEdge = 1.0f;
  const std::size_t budget = std::min(
      kMaxOctreeIndices, std::max(kOctreeEntriesPerLight * c.inOctree.size(), kMinOctreeBudget));
  SurfaceCells surfaces;
  for (;; leafEdge *= 2.0f) {
    const int finerLevels = o.levels;
    const float finerEdge = o.leafEdge;
    shape(o, c.domain, c.margin, leafEdge);
    if (!geometry.empty) {
      // A shape one level shallower over the same root has the cells of the one before
      // without its deepest level (their boxes as tight or tighter than found afresh).
      if (!surfaces.levels.empty() && o.levels + 1 == finerLevels &&
          o.leafEdge == 2.0f * finerEdge) {
        surfaces.levels.pop_back();
      } else {
        surfaces = surfaceCells(scene, o.origin, o.leafEdge, o.levels, c.margin);
      }
      // A shape whose lists plainly exceed the budget is not tried (one level always fits).
      if (o.levels > 1 &&
          octree::estimatedEntries(o, surfaces, c) > kProjectedOverBudget * double(budget))
        continue;
    }
    if (buildShape(o, c, geometry.empty ? nullptr : &surfaces, budget, options.dynamic, threads))
      break;
  }
  for (const auto& level : o.nodes) {
    for (const OctreeNode& n : level) {
      if (n.leaf) o.maxLeafCount = std::max(o.maxLeafCount, n.count);
    }
  }
  return o;
}

OctreeList octreeListAt(const LightOctree& o, glm::vec3 p) {
  const int deepest = o.levels - 1;
  const float cells = float(1u << deepest);
  const glm::vec3 q =
      glm::clamp(glm::floor((p - o.origin) / o.leafEdge), glm::vec3(0.0f), glm::vec3(cells - 1.0f));
  const glm::uvec3 cell(q);
  std::size_t index = 0;
  for (int level = 0;; ++level) {
    const OctreeNode& n = o.nodes[level][index];
    if (n.leaf) return {n.first, n.count};
    const glm::uvec3 c = (cell >> std::uint32_t(deepest - level - 1)) & 1u;
    const unsigned octant = c.x + 2 * c.y + 4 * c.z;
    if (!(n.childMask & (1u << octant))) return {0, 0};
    index = n.firstChild + std::size_t(__builtin_popcount(n.childMask & ((1u << octant) - 1)));
  }
}

bool lightReaches(const Light& light, glm::vec3 p) {
  if (!isRanged(light)) return true;
  const glm::dvec3 v = glm::dvec3(p) - glm::dvec3(light.position);
  const double d = glm::length(v);
  if (d >= double(light.range)) return false;
  if (light.type != LightType::Spot || d == 0.0) return true;
  const double outer = std::min(double(light.outerConeAngle), 1.5707963267948966);
  return glm::dot(v / d, glm::normalize(glm::dvec3(light.direction))) > std::cos(outer);
}

}  // namespace manylight
