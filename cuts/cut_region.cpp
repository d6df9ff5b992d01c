#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "bake/light_tree_layout.h"
#include "cuts/cut_heap.h"
#include "cuts/far_field.h"
#include "cuts/node_lanes.h"
#include "cuts/tile_cuts.h"

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
// times the target is given up as full: refining the rest would fill it anyway.
constexpr float kHopeless = 4.0f;
// Under the node rule, the folded entries' lobe spreads sum to at most this share of the
// target (cuts/tile_cuts.h: the far field's lobes are a constant over the group).
constexpr float kLobeFold = 0.5f;
// An entry folded into the far field (beside foldBounds' kZeroEntry and kFullCone).
constexpr float kFolded = 1.0f;

float maxOf(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// A bound per unit albedo `d` and one per unit specular colour `s`, weighed by the group's
// mean albedo and specular colour (the CPU's measure; each pixel checks with its own).
glm::vec3 weigh(const SpecularLobes& lobes, glm::vec3 d, glm::vec3 s) {
  return lobes.albedo * d + lobes.specular * s;
}

// Bounds per unit albedo `d` and per unit specular colour `s` added to (`total`) or joined
// with (the node rule) `to` and `toLobe`.
void join(bool total, glm::vec3& to, glm::vec3& toLobe, glm::vec3 d, glm::vec3 s) {
  to = total ? to + d : glm::max(to, d);
  toLobe = total ? toLobe + s : glm::max(toLobe, s);
}

}  // namespace

bool CutWorkspace::Foldable::operator<(const Foldable& o) const {
  return std::make_pair(maxOf(t), item) < std::make_pair(maxOf(o.t), o.item);
}

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
  // Nodes wait here for their items, and are evaluated kLanes at once (cuts/node_lanes.h),
  // then added in the order they came.
  struct Waiting {
    int tree, index;
    const Item* parent;  // its shading at the centre is the child's too when they share a light
  };
  Waiting waiting[kLanes];
  int waitingCount = 0;
  BoundLanes bounds;

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
  // (e⁺+2)/(2π)·cosᵣ⁺^e⁻] at every pixel, so the node per unit specular colour lies within
  // I⁻·that lower·cos⁻·window⁻(d⁺)/d⁺² and I⁺·that upper·cos⁺·window(d⁻)/d⁻². The
  // representative's lobe at the centre, along the mirror axis with the mean exponent, lies
  // within them too: the estimate of a folded entry's lobe, off by at most their spread.
  // `same`: an item with the same representative, whose lobe at the centre is this one's.
  void addLobe(Item& it, const Node& n, int l, const Item* same) const {
    constexpr float kTwoPi = 2.0f * kPi;
    const SpecularLobes& lobes = terms.g.lobes;
    const float cosR = std::clamp(bounds.mirrorCos[l], 0.0f, 1.0f);
    const float cosRLow = std::clamp(bounds.mirrorCosLow[l], 0.0f, 1.0f);
    // No light of the node on the group (upperScale 0), or no lower bound (lowerScale 0):
    // the powers are not needed.
    const float top = bounds.upperScale[l] <= 0.0f ? 0.0f
                      : cosR < 1.0f
                          ? (lobes.maxExponent + 2.0f) / kTwoPi * std::pow(cosR, lobes.minExponent)
                          : (lobes.maxExponent + 2.0f) / kTwoPi;
    const float bottom =
        cosRLow > 0.0f && bounds.lowerScale[l] > 0.0f
            ? (lobes.minExponent + 2.0f) / kTwoPi * std::pow(cosRLow, lobes.maxExponent)
            : 0.0f;
    const float slack = terms.slackRate * maxOf(n.intensity) + terms.slackFloor;
    const glm::vec3 upper = (n.intensity + slack) * (bounds.upperScale[l] * top);
    const glm::vec3 lower =
        glm::max(n.intensity - slack, glm::vec3(0.0f)) * (bounds.lowerScale[l] * bottom);
    it.lobeSpread = glm::max(upper - lower, glm::vec3(0.0f));
    it.lobeError = terms.total ? it.lobeSpread : upper;
    if (same) {
      it.lobeUnit = same->lobeUnit;
    } else {
      const glm::vec3 towards = it.tree == 0 ? n.repPoint : n.repPoint - terms.centre;
      const float length = glm::length(towards);
      const float c = length > 0.0f ? glm::dot(towards, lobes.axis) / length : 0.0f;
      it.lobeUnit = c > 0.0f && it.unit > 0.0f
                        ? it.unit * kPi * ((lobes.meanExponent + 2.0f) / kTwoPi) *
                              std::pow(c, lobes.meanExponent)
                        : 0.0f;
    }
    it.estimate = it.intensity * (lobes.albedo * it.unit + lobes.specular * it.lobeUnit);
    const bool bounded = !it.leaf && std::isfinite(it.measure);
    it.weighted = bounded ? weigh(lobes, it.error, it.lobeError) : glm::vec3(0.0f);
    if (bounded) it.measure = maxOf(it.weighted);
  }
  MANYLIGHT_INLINE void queue(int tree, int index, const Item* parent) {
    if (cutter.node(tree, index).representative < 0) return;  // empty: holds no light
    waiting[waitingCount++] = {tree, index, parent};
    if (waitingCount == kLanes) flush();
  }
  // The rule's target at the centre times `margin`, with `errors` the cut's summed errors.
  float target(float margin, glm::vec3 errors) const {
    return margin * rule.error * maxOf(rule.total ? sum - errors : sum);
  }
  // Whether the rule's measure of the cut (its largest bound `top`, or under the total rule
  // the sum `errors`) meets that target.
  bool holds(float margin, float top, glm::vec3 errors) const {
    const float have = rule.total ? maxOf(errors) : top;
    return std::isfinite(top) &&
           (have <= target(margin, errors) || (rule.total && have <= kAbsoluteFloor));
  }
  // Whether a cut of `size` entries, the largest bound `top`, can take no more refining.
  bool full(int size, float top) const {
    const int limit = finest || rule.total ? rule.maxCut : std::min(rule.maxCut, kSplitCut);
    return size + 1 > limit ||
           (!rule.total && 2 * size > limit && top > kHopeless * kMargin * rule.error * maxOf(sum));
  }
  float topOfHeap() const { return layout::floatOf(std::uint32_t(work.heap.front() >> 32)); }
};

RegionCut TileCutter::cutRegion(const ShadingRegion& region, const CutRule& rule, bool finest,
                                std::vector<std::uint32_t>& entries, const CutSeed* seed,
                                CutSeed* next) const {
  CutWorkspace work;
  return cutRegion(work, region, rule, finest, entries, seed, next);
}

// The cut's arithmetic runs eight nodes at a time (cuts/node_lanes.h): the children of up
// to four nodes refined at once, their bounds, the far field's fold bounds and sums.
RegionCut TileCutter::cutRegion(CutWorkspace& work, const ShadingRegion& g, const CutRule& rule,
                                bool finest, std::vector<std::uint32_t>& entries,
                                const CutSeed* seed, CutSeed* next) const {
  const glm::vec3 centre = 0.5f * (g.pMin + g.pMax);
  work.items.clear();
  work.settled.clear();
  work.heap.clear();
  Cut cut{*this,
          work,
          rule,
          finest,
          next != nullptr,
          RegionTerms{g, centre, 0.5f * glm::length(g.pMax - g.pMin),
                      0.25f * glm::dot(g.pMax - g.pMin, g.pMax - g.pMin), float(colour_.slack),
                      float(colour_.slackFloor), rule.total},
          RegionCut{},
          glm::vec3(0.0f),
          glm::vec3(0.0f),
          FarField(centre)};
  cut.terms.mirror = ShadingRegion{
      g.pMin, g.pMax, g.lobes.axis, g.lobes.cosSpread, g.lobes.sinSpread, SpecularLobes{}};
  if (seed) {
    cut.far = seed->far.movedTo(centre);
    cut.farCheck = seed->farCheck;
    cut.farLobeCheck = seed->farLobeCheck;
    cut.farLobeSpread = seed->farLobeSpread;
    const glm::vec3 farSum = cut.far.irradianceAtCentre(g.axis) / kPi;
    cut.sum += g.lobes.on ? weigh(g.lobes, farSum, cut.far.specular()) : farSum;
    if (rule.total)
      cut.errorSum += g.lobes.on ? weigh(g.lobes, cut.farCheck, cut.farLobeCheck) : cut.farCheck;
    for (const CutSeed::NodeRef& n : seed->nodes) cut.queue(n.tree, n.index, nullptr);
  } else {
    for (int t = 0; t < 3; ++t) {
      if (leaves_[t] > 0) cut.queue(t, 0, nullptr);
    }
  }
  cut.flush();
  if (!refine(cut)) return cut.result;
  fold(cut);
  emit(cut, entries, next);
  return cut.result;
}

bool TileCutter::refine(Cut& cut) const {
  using Item = CutWorkspace::Item;
  std::vector<std::uint64_t>& heap = cut.work.heap;
  const CutRule& rule = cut.rule;
  while (!heap.empty()) {
    const float top = cut.topOfHeap();
    if (cut.holds(kMargin, top, cut.errorSum)) break;
    const int size = int(heap.size() + cut.work.settled.size()) + cut.far.count();
    if (cut.full(size, top)) {
      // At the finest size, a full cut that meets the rule at the centre without the margin
      // is still shared: its pixels check it for themselves, and most pass (where a surface
      // meets another, 4×4 squares fill up just above the margin's target, and per-pixel
      // cuts there would be far larger).
      // Larger groups split instead: the quarters' cuts are smaller, and so cheaper per pixel.
      if (cut.finest && cut.holds(1.0f, top, cut.errorSum)) break;
      cut.result.perPixel = true;  // the tile's cut is full: its pixels cut for themselves
      const float want = cut.target(kMargin, cut.errorSum);
      const float have = rule.total ? maxOf(cut.errorSum) : top;
      cut.result.shortfall = want > 0.0f ? have / want : std::numeric_limits<float>::infinity();
      if (!cut.wantSeed) return false;
      break;  // still a seed
    }
    // Refine the top node and, while the rule asks it of them too (checked as if the nodes
    // refined so far had no error left), the next ones: up to kLanes / 2, so that all their
    // children's bounds are evaluated at once.
    Item parents[kLanes / 2];
    int count = 0;
    glm::vec3 errorLeft = cut.errorSum;
    do {
      cut_heap::popHeap(heap);
      const Item& parent = parents[count++] =
          cut.work.items[std::size_t(heap.back() & 0xffffffffu)];
      heap.pop_back();
      if (std::isfinite(parent.measure)) errorLeft -= parent.weighted;
    } while (count < kLanes / 2 && !heap.empty() &&
             !cut.holds(kMargin, cut.topOfHeap(), errorLeft) &&
             !cut.full(size + count, cut.topOfHeap()));
    cut.errorSum = errorLeft;
    for (int p = 0; p < count; ++p) {
      cut.sum -= parents[p].estimate;
      cut.queue(parents[p].tree, 2 * parents[p].index + 1, &parents[p]);
      cut.queue(parents[p].tree, 2 * parents[p].index + 2, &parents[p]);
    }
    cut.flush();
  }
  for (const std::uint64_t e : heap) cut.work.settled.push_back(int(e & 0xffffffffu));
  return true;
}

// The far field: directional, point and spot entries lighting every pixel of the tile from in
// front, folded into one linear function while the rule keeps a margin (far_field.h).
// Under the node rule an entry folds when its bound plus T stays within the margin the
// cut stopped at; under the total rule the smallest T fold first while the summed bound
// stays within kFoldMargin of the rule.
void TileCutter::fold(Cut& cut) const {
  CutWorkspace& work = cut.work;
  const CutRule& rule = cut.rule;
  RegionCut& result = cut.result;
  work.foldable.clear();
  // T for kLanes entries at once (cuts/node_lanes.h), or that an entry gives nothing in
  // the group (left out below) or is a spot with its cone at 1 (written as a point); lanes
  // past a batch's count keep earlier entries: evaluated, never read.
  FoldLanes& lights = work.lights;
  work.shape.assign(work.items.size(), -1.0f);
  int batch[kLanes], batchCount = 0;
  auto foldBatch = [&]() MANYLIGHT_INLINE {
    float t[kLanes];
    foldBounds(cut.terms, lights, batchCount, t);
    for (int b = 0; b < batchCount; ++b) {
      if (t[b] >= 0.0f) {
        work.foldable.push_back({batch[b], work.items[std::size_t(batch[b])].intensity * t[b]});
      } else {
        work.shape[std::size_t(batch[b])] = t[b];  // kZeroEntry, kFullCone or −1
      }
    }
    batchCount = 0;
  };
  for (const int k : work.settled) {
    const CutWorkspace::Item& it = work.items[std::size_t(k)];
    if (it.dark) continue;
    if (!it.leaf) join(rule.total, result.check, result.lobeCheck, it.error, it.lobeError);
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
  join(rule.total, result.check, result.lobeCheck, cut.farCheck, cut.farLobeCheck);
  foldEntries(cut);
}

void TileCutter::foldEntries(Cut& cut) const {
  using Foldable = CutWorkspace::Foldable;
  CutWorkspace& work = cut.work;
  const CutRule& rule = cut.rule;
  RegionCut& result = cut.result;
  const SpecularLobes& lobes = cut.terms.g.lobes;
  // A folded entry's lobe is the constant at the centre (FarField::addSpecular), within
  // [0, its lobe bound] at every pixel: an internal node's bound is in the check already, a
  // leaf's (exact when not folded) joins it.
  if (rule.total) {
    std::sort(work.foldable.begin(), work.foldable.end());
    for (const Foldable& f : work.foldable) {
      const CutWorkspace::Item& it = work.items[std::size_t(f.item)];
      const glm::vec3 b = result.check + f.t;
      const glm::vec3 bLobe = result.lobeCheck + (it.leaf ? it.lobeError : glm::vec3(0.0f));
      const glm::vec3 w = lobes.on ? weigh(lobes, b, bLobe) : b;
      if (maxOf(w) > kFoldMargin * rule.error * maxOf(cut.sum - w)) break;
      result.check = b;
      result.lobeCheck = bLobe;
      cut.farCheck += f.t + it.error;
      cut.farLobeCheck += it.lobeError;
      work.shape[std::size_t(f.item)] = kFolded;
    }
  } else {
    // The folded entries' lobes err together, each by at most its spread: their sum is one
    // more bound in the check (a node's, to the rule), and stays within kLobeFold of the
    // target; the entries with the least spread fold first.
    if (lobes.on) {
      auto spread = [&](const Foldable& f) {
        return maxOf(lobes.specular * work.items[std::size_t(f.item)].lobeSpread);
      };
      std::sort(work.foldable.begin(), work.foldable.end(),
                [&](const Foldable& a, const Foldable& b) {
                  return std::make_pair(spread(a), a.item) < std::make_pair(spread(b), b.item);
                });
    }
    const float target = kMargin * rule.error * maxOf(cut.sum);
    for (const Foldable& f : work.foldable) {
      const CutWorkspace::Item& it = work.items[std::size_t(f.item)];
      const glm::vec3 b = it.error + f.t;
      const glm::vec3 w = lobes.on ? weigh(lobes, b, it.lobeError) : b;
      if (maxOf(w) > target) continue;
      const glm::vec3 spread = cut.farLobeSpread + it.lobeSpread;
      if (lobes.on && maxOf(lobes.specular * spread) > kLobeFold * target) break;
      join(false, result.check, result.lobeCheck, b, it.lobeError);
      join(false, cut.farCheck, cut.farLobeCheck, b, it.lobeError);
      cut.farLobeSpread = spread;
      work.shape[std::size_t(f.item)] = kFolded;
    }
    result.lobeCheck = glm::max(result.lobeCheck, cut.farLobeSpread);
  }
}

// The cut's entries: the far field first, then tree by tree (the bounds are set by fold).
void TileCutter::emit(Cut& cut, std::vector<std::uint32_t>& entries, CutSeed* next) const {
  CutWorkspace& work = cut.work;
  RegionCut& result = cut.result;
  FarField& far = cut.far;
  if (next) next->nodes.clear();
  for (auto& e : work.byTree) e.clear();
  // Folded point and spot entries go into the far field kLanes at a time (addFarField).
  FarLanes& toFold = work.toFold;
  FarSums sums{};
  int foldCount = 0, summed = 0;
  auto foldLanes = [&]() MANYLIGHT_INLINE {
    addFarField(far.centre(), toFold, foldCount, sums);
    summed += foldCount;
    foldCount = 0;
  };
  for (const int k : work.settled) {
    const CutWorkspace::Item& it = work.items[std::size_t(k)];
    if (it.dark) continue;  // contributes nothing anywhere in the tile
    const Node& l = node(it.tree, it.index);
    const float entryShape = work.shape[std::size_t(k)];
    if (entryShape == kFolded) {
      if (cut.terms.g.lobes.on) far.addSpecular(it.intensity * it.lobeUnit);
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
    std::vector<std::uint32_t>& e = work.byTree[tree];
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
  result.lobes = cut.terms.g.lobes.on;
  result.farSpecular = far.specular();
  if (next) {
    next->far = far;
    next->farCheck = cut.farCheck;
    next->farLobeCheck = cut.farLobeCheck;
    next->farLobeSpread = cut.farLobeSpread;
    return;
  }
  if (result.lobes) {  // TileCuts' two texels of a cut with lobes
    for (const glm::vec3 v : {result.lobeCheck, result.farSpecular}) {
      for (int c = 0; c < 3; ++c) entries.push_back(layout::wordOf(v[c]));
      entries.push_back(0u);
    }
  }
  if (!far.empty()) far.write(entries);
  for (int t = 0; t < 3; ++t) {
    result.counts[t] = int(work.byTree[t].size() / (t == 2 ? 12 : 8));
    entries.insert(entries.end(), work.byTree[t].begin(), work.byTree[t].end());
  }
}

}  // namespace manylight
