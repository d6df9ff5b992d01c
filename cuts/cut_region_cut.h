#pragma once
// TileCutter::Cut: one shared cut in the making, and what it shares with cuts/cut_region.cpp,
// its only includer (an internal header, apart so that neither file passes 500 lines).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bake/light_tree_layout.h"
#include "cuts/cut_heap.h"
#include "cuts/far_field.h"
#include "cuts/node_lanes.h"
#include "cuts/tile_cuts.h"

namespace manylight {

namespace cut_region {

inline constexpr float kPi = 3.14159265358979323846f;
// The CPU stops refining once the rule holds against its estimate at the tile's centre
// times this margin, so that most pixels, whose estimates differ from the centre's, pass
// their own check: kMargin under the node rule, kTotalMargin under the total rule, whose
// far field then takes entries while the summed bound stays within kFoldMargin
// (cut_region.cpp). A pixel darker than the centre by more than the margin fails its check
// and walks its own cut. At 1/2 and 3/4 (the fold's), 680–1,311 of 58,600 pixels of the
// generated room with 4,096 uniform, mixed or specular mixed lights (320×240, ε = 0.02)
// failed and reached --max-cut in their walks; at 1/4 and 0.3 none do, for 10–25% more light
// evaluations a pixel (clustered lights: 0 either way, 8% slower).
inline constexpr float kMargin = 0.5f;
inline constexpr float kTotalMargin = 0.25f;
inline constexpr float kFoldMargin = 0.3f;
// Under the node rule, a cut past half the maximum whose largest bound is still this many
// times the target is given up as full: refining the rest would fill it anyway.
inline constexpr float kHopeless = 4.0f;

inline float maxOf(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// A bound per unit albedo `d` and one per unit specular colour `s`, weighed by the group's
// mean albedo and specular colour (the CPU's measure; each pixel checks with its own).
inline glm::vec3 weigh(const SpecularLobes& lobes, glm::vec3 d, glm::vec3 s) {
  return lobes.albedo * d + lobes.specular * s;
}

}  // namespace cut_region

// One cut in the making: its items (in the workspace), the heap of those still to refine,
// the running sums, the far field it starts from, and the nodes waiting to be bounded.
struct TileCutter::Cut {
  using Item = CutWorkspace::Item;
  const TileCutter& cutter;
  CutWorkspace& work;
  const CutRule& rule;
  bool finest;
  bool wantSeed;
  RegionTerms terms;
  RegionCut result;
  glm::vec3 sum{0.0f}, errorSum{0.0f};
  // The far field the cut starts from (a seed's, about the group's centre), and the bound of
  // the entries folded into it.
  FarField far;
  glm::vec3 farCheck{0.0f}, farLobeCheck{0.0f}, farLobeSpread{0.0f};
  FarRemainders farRemainders{};  // node rule: its entries' remainders T, summed by bin
  // Nodes wait here for their items, and are evaluated kLanes at once (cuts/node_lanes.h),
  // then added in the order they came.
  struct Waiting {
    int tree, index;
    const Item* parent;  // its shading at the centre is the child's too when they share a light
  };
  Waiting waiting[kLanes]{};
  int waitingCount = 0;
  BoundLanes bounds{};

  // A heap entry: the measure's bits above the item's index, so that one integer comparison
  // orders entries as (measure, index) pairs would.
  static std::uint64_t entry(float measure, int k) {
    return std::uint64_t(layout::wordOf(measure)) << 32 | std::uint32_t(k);
  }
  MANYLIGHT_INLINE void add(const Item& it) {
    if (it.representative < 0) return;  // empty: holds no light
    sum += it.estimate;
    if (it.measure > 0.0f && std::isfinite(it.measure)) errorSum += it.weighted;
    work.items.push_back(it);
    const int k = int(work.items.size()) - 1;
    if (it.measure > 0.0f) {
      if (!it.leaf) {  // likely refined later: fetch its children's nodes meanwhile
        const char* c = reinterpret_cast<const char*>(&cutter.node(it.tree, 2 * it.index + 1));
        for (int b = 0; b < int(2 * sizeof(Node)); b += 64) __builtin_prefetch(c + b);
      }
      work.heap.push_back(entry(it.measure, k));
      cut_heap::pushHeap(work.heap);
    } else {
      work.settled.push_back(k);
    }
  }
  // Lanes past a batch's count hold lane 0's node or earlier values: evaluated, never read.
  MANYLIGHT_INLINE void flush() {
    if (waitingCount == 0) return;
    const float* records[kLanes];
    NodeLanes& lanes = work.lanes;
    for (int l = 0; l < waitingCount; ++l) {
      const Waiting& w = waiting[l];
      const Node& n = cutter.node(w.tree, w.index);
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
      const Node& n = cutter.node(w.tree, w.index);
      ++result.bounds;
      Item it{bounds.measure[l],
              w.tree,
              w.index,
              {bounds.error[0][l], bounds.error[1][l], bounds.error[2][l]},
              {bounds.estimate[0][l], bounds.estimate[1][l], bounds.estimate[2][l]},
              bounds.dark[l] != 0.0f,
              n.leaf(),
              n.representative,
              bounds.unit[l],
              n.intensity};
      it.weighted = it.error;
      if (terms.g.lobes.on)
        addLobe(it, n, l,
                w.parent && w.parent->representative == n.representative ? w.parent : nullptr);
      add(it);
    }
    waitingCount = 0;
  }
  // The Phong lobe of the group's specular pixels (ShadingRegion::lobes) over item `it` of
  // node `n`, lane l of `bounds`. With cosᵣ⁺ and cosᵣ⁻ the largest and smallest cosines
  // between a mirror direction and a direction into the node (BoundLanes) and exponents in
  // [e⁻, e⁺], the lobe (e+2)/(2π)·max(l·m, 0)^e lies within [(e⁻+2)/(2π)·cosᵣ⁻^e⁺,
  // (e⁺+2)/(2π)·cosᵣ⁺^e⁻] at every pixel (the powers bounded by BoundLanes' lobeBottom and
  // lobeTop), so the node per unit specular colour lies within
  // I⁻·that lower·cos⁻·window⁻(d⁺)/d⁺² and I⁺·that upper·cos⁺·window(d⁻)/d⁻² (a spot's
  // times its cone factor's bounds: BoundLanes' lowerScale and upperScale hold them). The
  // representative's lobe at the centre, along the mirror axis with the mean exponent, lies
  // within them too: the estimate of a folded entry's lobe, off by at most their spread.
  // `same`: an item with the same representative, whose lobe at the centre is this one's.
  void addLobe(Item& it, const Node& n, int l, const Item* same) const {
    constexpr float kTwoPi = 2.0f * cut_region::kPi;
    const SpecularLobes& lobes = terms.g.lobes;
    const float top = (lobes.maxExponent + 2.0f) / kTwoPi * bounds.lobeTop[l];
    const float bottom = (lobes.minExponent + 2.0f) / kTwoPi * bounds.lobeBottom[l];
    const float slack = terms.slackRate * cut_region::maxOf(n.intensity) + terms.slackFloor;
    const glm::vec3 upper = (n.intensity + slack) * (bounds.upperScale[l] * top);
    const glm::vec3 lower =
        glm::max(n.intensity - slack, glm::vec3(0.0f)) * (bounds.lowerScale[l] * bottom);
    it.lobeSpread = glm::max(upper - lower, glm::vec3(0.0f));
    it.lobeError = terms.total ? it.lobeSpread : upper;
    if (same) {
      it.lobeUnit = same->lobeUnit;
    } else {
      it.lobeUnit = it.unit > 0.0f
                        ? it.unit * cut_region::kPi * ((lobes.meanExponent + 2.0f) / kTwoPi) *
                              bounds.lobeTowards[l]
                        : 0.0f;
    }
    it.estimate = it.intensity * (lobes.albedo * it.unit + lobes.specular * it.lobeUnit);
    const bool bounded = !it.leaf && std::isfinite(it.measure);
    it.weighted = bounded ? cut_region::weigh(lobes, it.error, it.lobeError) : glm::vec3(0.0f);
    if (bounded) it.measure = cut_region::maxOf(it.weighted);
  }
  MANYLIGHT_INLINE void queue(int tree, int index, const Item* parent) {
    if (cutter.node(tree, index).representative < 0) return;  // empty: holds no light
    waiting[waitingCount++] = {tree, index, parent};
    if (waitingCount == kLanes) flush();
  }
  // The margin the cut stops at (kMargin, kTotalMargin).
  float margin() const { return rule.total ? cut_region::kTotalMargin : cut_region::kMargin; }
  // The rule's target at the centre times `margin`, with `errors` the cut's summed errors.
  float target(float margin, glm::vec3 errors) const {
    return margin * rule.error * cut_region::maxOf(rule.total ? sum - errors : sum);
  }
  // Whether the rule's measure of the cut (its largest bound `top`, or under the total rule
  // the sum `errors`) meets that target.
  bool holds(float margin, float top, glm::vec3 errors) const {
    const float have = rule.total ? cut_region::maxOf(errors) : top;
    return std::isfinite(top) &&
           (have <= target(margin, errors) || (rule.total && have <= kAbsoluteFloor));
  }
  // Whether a cut of `size` entries, the largest bound `top`, can take no more refining.
  bool full(int size, float top) const {
    const int limit = finest || rule.total ? rule.maxCut : splitCut(rule);
    return size + 1 > limit || (!rule.total && 2 * size > limit &&
                                top > cut_region::kHopeless * cut_region::kMargin * rule.error *
                                          cut_region::maxOf(sum));
  }
  // Under the total rule, whether a full cut (its largest bound `top`, its shortfall found)
  // is shared as the best its pixels can have, marked RegionCut::full, rather than left to
  // smaller groups or its pixels' own cuts: where every node's bound (upper − lower) is within
  // kTotalMargin · ε of the estimate at the centre, at the finest size or where the cut is too
  // far from the rule for quarters to meet it (kSplitShortfall). In 16×16 squares of a 96×72
  // image of 65,536 mixed lights, nodes up to 4,000 times over ε left pixels 175% off at the
  // 99th percentile; at the finest size without the condition, 16,384 clustered lights at
  // ε = 0.005 (320×240) left the worst pixel 3.5% off, against 0.35% with pixels walking
  // their own cuts. Never while a node is unbounded (a shading point in its box: its estimate
  // may be anything); smaller groups leave such nodes out.
  bool sharedFull(float top) const {
    if (!std::isfinite(top)) return false;
    return (finest || !(result.shortfall < kSplitShortfall)) &&
           top <= cut_region::kTotalMargin * rule.error * cut_region::maxOf(sum);
  }
  float topOfHeap() const { return layout::floatOf(std::uint32_t(work.heap.front() >> 32)); }
};

}  // namespace manylight
