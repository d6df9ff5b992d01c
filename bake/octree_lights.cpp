#include "bake/octree_lights.h"

#include <algorithm>
#include <utility>

#include "bake/light_pack.h"
#include "base/parallel.h"

namespace manylight::octree {

namespace {

// Fewer items than this are handled on one thread: starting threads would cost more.
constexpr std::size_t kParallelItems = std::size_t(1) << 15;
// Lights estimatedEntries samples, and the rows of cells it scans at most.
constexpr std::size_t kEstimateSample = 1024;
constexpr std::size_t kEstimateRows = std::size_t(1) << 18;

int threadsFor(std::size_t items, int threads) { return items < kParallelItems ? 1 : threads; }

// Runs work(k, begin, end) over [0, n) in chunks k = 0 … threadsFor(n, threads) − 1.
template <typename Work>
void forChunks(std::size_t n, int threads, const Work& work) {
  const std::size_t t = std::size_t(threadsFor(n, threads));
  runOnThreads(int(t), [&](int k) {
    work(std::size_t(k), n * std::size_t(k) / t, n * std::size_t(k + 1) / t);
  });
}

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// std::sort's result (the items are distinct), from one sorted chunk per thread merged in
// pairs.
template <typename T>
void parallelSort(std::vector<T>& v, int threads) {
  const std::size_t parts = std::size_t(threadsFor(v.size(), threads));
  std::vector<std::size_t> bound(parts + 1);
  for (std::size_t k = 0; k <= parts; ++k) bound[k] = v.size() * k / parts;
  runOnThreads(int(parts), [&](int k) {
    std::sort(v.begin() + std::ptrdiff_t(bound[std::size_t(k)]),
              v.begin() + std::ptrdiff_t(bound[std::size_t(k) + 1]));
  });
  for (std::size_t width = 1; width < parts; width *= 2) {
    const std::size_t merges = (parts + 2 * width - 1) / (2 * width);
    runOnThreads(int(merges), [&](int m) {
      const std::size_t lo = 2 * width * std::size_t(m);
      const std::size_t mid = std::min(lo + width, parts), hi = std::min(lo + 2 * width, parts);
      if (mid < hi)
        std::inplace_merge(v.begin() + std::ptrdiff_t(bound[lo]),
                           v.begin() + std::ptrdiff_t(bound[mid]),
                           v.begin() + std::ptrdiff_t(bound[hi]));
    });
  }
}

Box unite(const Box& a, const Box& b) { return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }

const Box kNoBox{glm::vec3(INFINITY), glm::vec3(-INFINITY)};

enum Kind : std::uint8_t { kUnranged, kInOctree, kUnreached, kWholeScene };

}  // namespace

std::vector<int> octreeOrder(const std::vector<Light>& lights, int threads) {
  std::vector<int> order;
  for (int i : lightOrder(lights).scene) {
    if (!isRanged(lights[std::size_t(i)])) order.push_back(i);
  }
  std::vector<Box> boxes(std::size_t(threadsFor(lights.size(), threads)), kNoBox);
  forChunks(lights.size(), threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    Box& box = boxes[k];
    for (std::size_t i = begin; i < end; ++i) {
      if (isRanged(lights[i])) box = unite(box, {lights[i].position, lights[i].position});
    }
  });
  Box box = kNoBox;
  for (const Box& b : boxes) box = unite(box, b);
  const std::size_t unranged = order.size();
  std::vector<std::pair<std::uint64_t, int>> coded(lights.size() - unranged);
  std::vector<std::size_t> firstCoded(lights.size() + 1, 0);
  for (std::size_t i = 0; i < lights.size(); ++i)
    firstCoded[i + 1] = firstCoded[i] + (isRanged(lights[i]) ? 1 : 0);
  const glm::vec3 scale = 2097151.0f / glm::max(box.hi - box.lo, glm::vec3(1e-30f));
  forChunks(lights.size(), threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (!isRanged(lights[i])) continue;
      const glm::vec3 q =
          glm::clamp((lights[i].position - box.lo) * scale, glm::vec3(0.0f), glm::vec3(2097151.0f));
      coded[firstCoded[i]] = {spread(std::uint64_t(q.x)) | spread(std::uint64_t(q.y)) << 1 |
                                  spread(std::uint64_t(q.z)) << 2,
                              int(i)};
    }
  });
  parallelSort(coded, threads);
  order.resize(unranged + coded.size());
  for (std::size_t k = 0; k < coded.size(); ++k) order[unranged + k] = coded[k].second;
  return order;
}

Classified classify(const std::vector<Light>& lights, const Bounds& geometry, bool dynamic,
                    int threads, LightOctree& o) {
  const std::size_t n = o.order.size();
  Classified c;
  c.supports.resize(n);
  std::vector<Box> boxes(std::size_t(threadsFor(n, threads)), kNoBox);
  forChunks(n, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    for (std::size_t slot = begin; slot < end; ++slot) {
      const Light& light = lights[std::size_t(o.order[slot])];
      if (!isRanged(light)) continue;
      c.supports[slot] = supportOf(light);
      boxes[k] = unite(boxes[k], sphereBox(c.supports[slot]));
    }
  });
  Box scene = kNoBox;
  for (const Box& b : boxes) scene = unite(scene, b);
  if (!(scene.lo.x <= scene.hi.x)) scene = {glm::vec3(0.0f), glm::vec3(0.0f)};
  if (!geometry.empty) scene = {geometry.min, geometry.max};
  const float scale = std::max(
      {glm::length(scene.lo), glm::length(scene.hi), glm::length(scene.hi - scene.lo), 1e-3f});
  const float margin = 1e-5f * scale;
  c.margin = margin;
  const Box grown = grow(scene, margin);
  const bool inScene = dynamic && !geometry.empty;  // moving lights stay octree lights
  std::vector<Kind> kinds(n, kUnranged);
  std::fill(boxes.begin(), boxes.end(), kNoBox);
  forChunks(n, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    for (std::size_t slot = begin; slot < end; ++slot) {
      const Support& s = c.supports[slot];
      if (!(s.range > 0.0f)) continue;
      const bool holds = !geometry.empty && contains(s, grown, margin);
      if (inScene && !holds) {
        kinds[slot] = kInOctree;  // its lists are found wherever it moves
      } else if (!overlaps(s, grown, margin)) {
        kinds[slot] = kUnreached;
      } else if (holds) {
        kinds[slot] = kWholeScene;
      } else {
        kinds[slot] = kInOctree;
        const Box b = sphereBox(s);
        boxes[k] = unite(boxes[k], {glm::max(b.lo, scene.lo), glm::min(b.hi, scene.hi)});
      }
    }
  });
  c.domain = kNoBox;
  for (const Box& b : boxes) c.domain = unite(c.domain, b);
  if (!(c.domain.lo.x <= c.domain.hi.x) || inScene) c.domain = scene;
  for (std::size_t slot = 0; slot < n; ++slot) {
    const int index = o.order[slot];
    switch (kinds[slot]) {
      case kUnranged:
        o.global.push_back(std::uint32_t(slot));
        break;
      case kInOctree:
        c.inOctree.push_back(std::uint32_t(slot));
        break;
      case kUnreached:
        o.unreached.push_back(index);
        break;
      case kWholeScene:
        o.wholeScene.push_back(index);
        o.global.push_back(std::uint32_t(slot));
        break;
    }
  }
  return c;
}

float quarterMedianRadius(const std::vector<Support>& supports,
                          const std::vector<std::uint32_t>& slots) {
  if (slots.empty()) return 0.0f;
  std::vector<float> radii(slots.size());
  for (std::size_t k = 0; k < slots.size(); ++k) radii[k] = supports[slots[k]].radius;
  std::nth_element(radii.begin(), radii.begin() + std::ptrdiff_t(radii.size() / 2), radii.end());
  return 0.25f * radii[radii.size() / 2];
}

double estimatedEntries(const LightOctree& o, const SurfaceCells& surfaces,
                        const Classified& lights) {
  const std::vector<SurfaceCell>& cells = surfaces.levels.back();
  const std::size_t n = lights.inOctree.size();
  if (n == 0 || cells.empty()) return 0.0;
  const std::size_t step = std::max<std::size_t>(1, n / kEstimateSample);
  const glm::vec3 top(float((1u << (o.levels - 1)) - 1));
  double entries = 0.0;
  std::size_t sampled = 0, rows = 0;
  for (std::size_t k = 0; k < n && rows < kEstimateRows; k += step, ++sampled) {
    const Support& s = lights.supports[lights.inOctree[k]];
    const Box b = grow(sphereBox(s), o.margin);
    const glm::uvec3 lo(
        glm::clamp(glm::floor((b.lo - o.origin) / o.leafEdge), glm::vec3(0.0f), top));
    const glm::uvec3 hi(
        glm::clamp(glm::floor((b.hi - o.origin) / o.leafEdge), glm::vec3(0.0f), top));
    for (std::uint32_t z = lo.z; z <= hi.z; ++z) {
      for (std::uint32_t y = lo.y; y <= hi.y; ++y, ++rows) {
        const std::uint64_t last = surfaceCellKey({hi.x, y, z});
        auto it = std::lower_bound(
            cells.begin(), cells.end(), surfaceCellKey({lo.x, y, z}),
            [](const SurfaceCell& cell, std::uint64_t key) { return cell.key < key; });
        for (; it != cells.end() && it->key <= last; ++it)
          entries += overlaps(s, {it->lo, it->hi}, o.margin) ? 1.0 : 0.0;
      }
    }
  }
  return entries * double(n) / double(sampled);
}

}  // namespace manylight::octree
