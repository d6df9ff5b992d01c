#include "render/tile_cuts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bake/light_tree_layout.h"
#include "render/cut_heap.h"
#include "render/far_field.h"
#include "render/node_lanes.h"

namespace manylight {

namespace {

constexpr float kPi = 3.14159265358979323846f;
// The CPU stops refining once the rule holds against its estimate at the tile's centre
// times this margin, so that most pixels, whose estimates differ from the centre's, pass
// their own check.
constexpr float kMargin = 0.5f;
// Under the total rule, entries fold into the far field while the summed bound stays within
// this share of the rule's target (the cut itself stopped at kMargin).
constexpr float kFoldMargin = 0.75f;
// Under the node rule, a cut past half the maximum whose largest bound is still this many
// times the target is given up as full: refining the rest would fill it anyway (on 65,536
// mixed, uniform and clustered lights the cuts and images are the same as without, and
// 6% fewer bounds are evaluated).
constexpr float kHopeless = 4.0f;
// An entry folded into the far field (beside foldBounds' kZeroEntry and kFullCone).
constexpr float kFolded = 1.0f;

float maxOf(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

}  // namespace

// The cut's arithmetic runs eight nodes at a time (render/node_lanes.h): the children of up
// to four nodes refined at once, their bounds, the far field's fold bounds and sums. On
// 65,536 mixed lights at 640x480 (best of 5 repeats in a frame) the CPU cut took 135 ms one
// node at a time (with this function compiled for AVX2, which now makes no difference), 107
// with the node bounds in lanes, 89.5 with the fold bounds too, 80 with nodes gathered by a
// transpose, 73 with the far field's sums. Errors against the reference stayed the same.
RegionCut TileCutter::cutRegion(const ShadingRegion& g, const CutRule& rule, bool finest,
                                std::vector<std::uint32_t>& entries, const CutSeed* seed,
                                CutSeed* next) const {
  RegionCut result;
  const glm::vec3 centre = 0.5f * (g.pMin + g.pMax);
  const float slackRate = float(colour_.slack), slackFloor = float(colour_.slackFloor);

  struct Item {
    float measure;  // what the rule refines by; +inf: unbounded; −1: a leaf (never refined)
    int tree, index;
    glm::vec3 error;     // upper (node rule) or upper − lower (total rule)
    glm::vec3 estimate;  // at the tile's centre
    bool dark;           // no light of the node reaches any point of the tile
    bool leaf;
    int representative;
    float unit;           // the representative's shading at the centre per unit intensity
    glm::vec3 intensity;  // decoded (internal nodes) or exact (leaves)
  };

  // The cut: items refined no further (leaves, empty and dark nodes) and a max-heap of the
  // others by measure.
  // Kept per thread between tiles: allocating them per tile costs more than the cut.
  thread_local std::vector<Item> items;
  thread_local std::vector<int> settled;
  // A heap entry is one word, the measure's bits above the item's index: positive floats
  // (and +inf) order as their bits do, so this orders as (measure, index) pairs would, with
  // one integer comparison.
  thread_local std::vector<std::uint64_t> heap;
  auto entry = [](float measure, int k) MANYLIGHT_INLINE {
    return std::uint64_t(layout::wordOf(measure)) << 32 | std::uint32_t(k);
  };
  items.clear();
  settled.clear();
  heap.clear();
  glm::vec3 sum(0.0f), errorSum(0.0f);
  auto add = [&](const Item& it) MANYLIGHT_INLINE {
    if (it.representative < 0) return;  // empty: holds no light
    sum += it.estimate;
    if (it.measure > 0.0f && std::isfinite(it.measure)) errorSum += it.error;
    items.push_back(it);
    const int k = int(items.size()) - 1;
    if (it.measure > 0.0f) {
      if (!it.leaf) {  // likely refined later: fetch its children's nodes meanwhile
        const char* c = reinterpret_cast<const char*>(&node(it.tree, 2 * it.index + 1));
        for (int b = 0; b < int(2 * sizeof(Node)); b += 64) __builtin_prefetch(c + b);
      }
      heap.push_back(entry(it.measure, k));
      cut_heap::pushHeap(heap);
    } else {
      settled.push_back(k);
    }
  };
  // Nodes wait here for their items, and are evaluated kLanes at once (render/node_lanes.h),
  // then added in the order they came.
  const RegionTerms terms{g,
                          centre,
                          0.5f * glm::length(g.pMax - g.pMin),
                          0.25f * glm::dot(g.pMax - g.pMin, g.pMax - g.pMin),
                          slackRate,
                          slackFloor,
                          rule.total};
  struct Waiting {
    int tree, index;
    const Item* parent;  // its shading at the centre is the child's too when they share a light
  };
  Waiting waiting[kLanes];
  int waitingCount = 0;
  // Lanes past a batch's count hold lane 0's node or earlier values: evaluated, never read.
  thread_local NodeLanes lanes;
  BoundLanes bounds;
  auto flush = [&]() MANYLIGHT_INLINE {
    if (waitingCount == 0) return;
    const float* records[kLanes];
    for (int l = 0; l < waitingCount; ++l) {
      const Waiting& w = waiting[l];
      const Node& n = node(w.tree, w.index);
      records[l] = &n.boxMin.x;
      lanes.tree[l] = float(w.tree);
      const bool known = w.parent && w.parent->representative == n.representative;
      lanes.knownUnit[l] = known ? 1.0f : 0.0f;
      lanes.unit[l] = known ? w.parent->unit : 0.0f;
    }
    gatherNodes(records, waitingCount, lanes);
    nodeBounds(terms, lanes, waitingCount, bounds);
    for (int l = 0; l < waitingCount; ++l) {
      const Waiting& w = waiting[l];
      const Node& n = node(w.tree, w.index);
      ++result.bounds;
      add(Item{bounds.measure[l],
               w.tree,
               w.index,
               {bounds.error[0][l], bounds.error[1][l], bounds.error[2][l]},
               {bounds.estimate[0][l], bounds.estimate[1][l], bounds.estimate[2][l]},
               bounds.dark[l] != 0.0f,
               n.leaf(),
               n.representative,
               bounds.unit[l],
               n.intensity});
    }
    waitingCount = 0;
  };
  auto queue = [&](int tree, int index, const Item* parent) MANYLIGHT_INLINE {
    if (node(tree, index).representative < 0) return;  // empty: holds no light
    waiting[waitingCount++] = {tree, index, parent};
    if (waitingCount == kLanes) flush();
  };
  // The far field the cut starts from (a seed's, about this group's centre), and the bound of
  // the entries folded into it.
  FarField far(centre);
  glm::vec3 farCheck(0.0f);
  if (seed) {
    far = seed->far.movedTo(centre);
    farCheck = seed->farCheck;
    sum += far.irradianceAtCentre(g.axis) / kPi;
    if (rule.total) errorSum += farCheck;
    for (const CutSeed::NodeRef& n : seed->nodes) queue(n.tree, n.index, nullptr);
  } else {
    for (int t = 0; t < 3; ++t) {
      if (leaves_[t] > 0) queue(t, 0, nullptr);
    }
  }
  flush();
  // The rule's target at the centre times `margin`, with `errors` the cut's summed errors.
  auto target = [&](float margin, glm::vec3 errors) {
    return margin * rule.error * maxOf(rule.total ? sum - errors : sum);
  };
  // Whether the rule's measure of the cut (its largest bound `top`, or under the total rule
  // the sum `errors`) meets that target.
  auto holds = [&](float margin, float top, glm::vec3 errors) {
    const float have = rule.total ? maxOf(errors) : top;
    return std::isfinite(top) &&
           (have <= target(margin, errors) || (rule.total && have <= kAbsoluteFloor));
  };
  // Whether a cut of `size` entries, the largest bound `top`, can take no more refining.
  const int limit = finest || rule.total ? rule.maxCut : std::min(rule.maxCut, kSplitCut);
  auto full = [&](int size, float top) {
    return size + 1 > limit ||
           (!rule.total && 2 * size > limit && top > kHopeless * kMargin * rule.error * maxOf(sum));
  };
  auto topOfHeap = [&] { return layout::floatOf(std::uint32_t(heap.front() >> 32)); };
  while (!heap.empty()) {
    const float top = topOfHeap();
    if (holds(kMargin, top, errorSum)) break;
    const int size = int(heap.size() + settled.size()) + far.count();
    if (full(size, top)) {
      // At the finest size, a full cut that meets the rule at the centre without the margin
      // is still shared: its pixels check it for themselves, and most pass (where a surface
      // meets another, 4×4 squares of 65,536 mixed lights filled up 1.0–1.5× above the
      // margin's target, and their pixels walked cuts of their own, 4,000 node bounds each).
      // Larger groups split instead: the quarters' cuts are smaller, and so cheaper per pixel.
      if (finest && holds(1.0f, top, errorSum)) break;
      result.perPixel = true;  // the tile's cut is full: its pixels cut for themselves
      const float want = target(kMargin, errorSum), have = rule.total ? maxOf(errorSum) : top;
      result.shortfall = want > 0.0f ? have / want : std::numeric_limits<float>::infinity();
      if (!next) return result;
      break;  // still a seed
    }
    // Refine the top node and, while the rule asks it of them too (checked as if the nodes
    // refined so far had no error left), the next ones: up to kLanes / 2, so that all their
    // children's bounds are evaluated at once.
    Item parents[kLanes / 2];
    int count = 0;
    glm::vec3 errorLeft = errorSum;
    do {
      cut_heap::popHeap(heap);
      const Item& parent = parents[count++] = items[std::size_t(heap.back() & 0xffffffffu)];
      heap.pop_back();
      if (std::isfinite(parent.measure)) errorLeft -= parent.error;
    } while (count < kLanes / 2 && !heap.empty() && !holds(kMargin, topOfHeap(), errorLeft) &&
             !full(size + count, topOfHeap()));
    errorSum = errorLeft;
    for (int p = 0; p < count; ++p) {
      sum -= parents[p].estimate;
      queue(parents[p].tree, 2 * parents[p].index + 1, &parents[p]);
      queue(parents[p].tree, 2 * parents[p].index + 2, &parents[p]);
    }
    flush();
  }
  for (const std::uint64_t e : heap) settled.push_back(int(e & 0xffffffffu));

  // The far field: directional, point and spot entries lighting every pixel of the tile from in
  // front, folded into one linear function while the rule keeps a margin (far_field.h).
  // Under the node rule an entry folds when its bound plus T stays within the margin the
  // cut stopped at; under the total rule the smallest T fold first while the summed bound
  // stays within kFoldMargin of the rule.
  struct Foldable {
    int item;
    glm::vec3 t;                               // T per channel
    bool operator<(const Foldable& o) const {  // smallest T first
      return std::make_pair(maxOf(t), item) < std::make_pair(maxOf(o.t), o.item);
    }
  };
  thread_local std::vector<Foldable> foldable;
  foldable.clear();
  // T for kLanes entries at once (render/node_lanes.h), or that an entry gives nothing in
  // the group (left out below) or is a spot with its cone at 1 (written as a point); lanes
  // past a batch's count keep earlier entries: evaluated, never read.
  thread_local FoldLanes lights;
  // Per item: kFolded once it is folded below, else foldBounds' answer where it cannot fold
  // (kZeroEntry, kFullCone), else −1.
  thread_local std::vector<float> shape;
  shape.assign(items.size(), -1.0f);
  int batch[kLanes], batchCount = 0;
  auto foldBatch = [&]() MANYLIGHT_INLINE {
    float t[kLanes];
    foldBounds(terms, lights, batchCount, t);
    for (int b = 0; b < batchCount; ++b) {
      if (t[b] >= 0.0f) {
        foldable.push_back({batch[b], items[std::size_t(batch[b])].intensity * t[b]});
      } else {
        shape[std::size_t(batch[b])] = t[b];  // kZeroEntry, kFullCone or −1
      }
    }
    batchCount = 0;
  };
  for (const int k : settled) {
    const Item& it = items[std::size_t(k)];
    if (it.dark) continue;
    if (!it.leaf)
      result.check = rule.total ? result.check + it.error : glm::max(result.check, it.error);
    const Node& l = node(it.tree, it.index);  // its representative's light: l.rep…
    const int b = batchCount++;
    batch[b] = k;
    lights.tree[b] = float(it.tree);
    for (int c = 0; c < 3; ++c) {
      lights.repPoint[c][b] = l.repPoint[c];
      lights.repAxis[c][b] = l.repAxis[c];
    }
    lights.repInvRange2[b] = l.repInvRange2;
    lights.repCos[b] = l.repCos;
    lights.coneScale[b] = l.repConeScale;
    lights.coneOffset[b] = l.repConeOffset;
    if (batchCount == kLanes) foldBatch();
  }
  if (batchCount > 0) foldBatch();
  result.check = rule.total ? result.check + farCheck : glm::max(result.check, farCheck);
  if (rule.total) {
    std::sort(foldable.begin(), foldable.end());
    for (const Foldable& f : foldable) {
      const glm::vec3 b = result.check + f.t;
      if (maxOf(b) > kFoldMargin * rule.error * maxOf(sum - b)) break;
      result.check = b;
      farCheck += f.t + items[std::size_t(f.item)].error;
      shape[std::size_t(f.item)] = kFolded;
    }
  } else {
    for (const Foldable& f : foldable) {
      const glm::vec3 b = items[std::size_t(f.item)].error + f.t;
      if (maxOf(b) > kMargin * rule.error * maxOf(sum)) continue;
      result.check = glm::max(result.check, b);
      farCheck = glm::max(farCheck, b);
      shape[std::size_t(f.item)] = kFolded;
    }
  }

  // The cut's entries: the far field first, then tree by tree (the bounds are set above).
  if (next) next->nodes.clear();
  thread_local std::vector<std::uint32_t> byTree[3];
  for (auto& e : byTree) e.clear();
  // Folded point and spot entries go into the far field kLanes at a time (addFarField).
  thread_local FarLanes toFold;
  FarSums sums{};
  int foldCount = 0, summed = 0;
  auto foldLanes = [&]() MANYLIGHT_INLINE {
    addFarField(far.centre(), toFold, foldCount, sums);
    summed += foldCount;
    foldCount = 0;
  };
  for (const int k : settled) {
    const Item& it = items[std::size_t(k)];
    if (it.dark) continue;  // contributes nothing anywhere in the tile
    const Node& l = node(it.tree, it.index);
    const float entryShape = shape[std::size_t(k)];
    if (entryShape == kFolded) {
      if (it.tree == 0) {
        far.addDirectional(l.repPoint, it.intensity);
        continue;
      }
      const int f = foldCount++;
      for (int c = 0; c < 3; ++c) {
        toFold.position[c][f] = l.repPoint[c];
        toFold.coneAxis[c][f] = l.repAxis[c];
        toFold.intensity[c][f] = it.intensity[c];
      }
      toFold.invRange2[f] = l.repInvRange2;
      toFold.spot[f] = it.tree == 2 ? 1.0f : 0.0f;
      toFold.coneScale[f] = l.repConeScale;
      toFold.coneOffset[f] = l.repConeOffset;
      if (foldCount == kLanes) foldLanes();
      continue;
    }
    if (next) {
      next->nodes.push_back({it.tree, it.index});
      continue;
    }
    // An entry that gives nothing anywhere in the group is left out (its bound stays in
    // the check); a spot whose cone is 1 towards all of the group is written as a point.
    if (entryShape == kZeroEntry) {
      ++result.zeros;
      continue;
    }
    const int tree = entryShape == kFullCone ? 1 : it.tree;
    // The representative itself: direction or position, and 1/range²; a spot's cone; the
    // node's intensity.
    std::vector<std::uint32_t>& e = byTree[tree];
    for (const float w :
         {l.repPoint.x, l.repPoint.y, l.repPoint.z, it.tree == 0 ? 0.0f : l.repInvRange2})
      e.push_back(layout::wordOf(w));
    float coneOffset = 0.0f;
    if (tree == 2) {
      for (const float w : {l.repAxis.x, l.repAxis.y, l.repAxis.z, l.repConeScale})
        e.push_back(layout::wordOf(w));
      coneOffset = l.repConeOffset;
    }
    for (const float w : {it.intensity.x, it.intensity.y, it.intensity.z, coneOffset})
      e.push_back(layout::wordOf(w));
  }
  if (foldCount > 0) foldLanes();
  if (summed > 0) far.add(sums, summed);
  result.folded = far.count();
  if (next) {
    next->far = far;
    next->farCheck = farCheck;
    return result;
  }
  if (!far.empty()) far.write(entries);
  for (int t = 0; t < 3; ++t) {
    result.counts[t] = int(byTree[t].size() / (t == 2 ? 12 : 8));
    entries.insert(entries.end(), byTree[t].begin(), byTree[t].end());
  }
  return result;
}

}  // namespace manylight
