#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cuts/cut_region_cut.h"

namespace manylight {

using cut_region::kFoldMargin;
using cut_region::kHopeless;
using cut_region::kMargin;
using cut_region::kPi;
using cut_region::maxOf;
using cut_region::weigh;

namespace {

// Under the node rule, the folded entries' lobe spreads sum to at most this share of the
// target (cuts/tile_cuts.h: the far field's lobes are a constant over the group). A pixel
// checks the cut's largest Lambert bound plus its largest lobe bound (or this sum, where
// larger) against its own estimate, while the CPU stopped where each node's two parts
// together met kMargin of the centre's estimate. At half the target, the pixels around a
// light's highlight on a glossy surface, whose estimates fall off from the centre's, failed
// their check and walked their own cuts (750 pixels of the generated specular room at
// 640 × 480, 65,536 lights; 210 at an eighth, for 1% more entries).
constexpr float kLobeFold = 0.125f;
// An entry folded into the far field (beside foldBounds' kZeroEntry and kFullCone).
constexpr float kFolded = 1.0f;

// Bounds per unit albedo `d` and per unit specular colour `s` added to (`total`) or joined
// with (the node rule) `to` and `toLobe`.
void join(bool total, glm::vec3& to, glm::vec3& toLobe, glm::vec3 d, glm::vec3 s) {
  to = total ? to + d : glm::max(to, d);
  toLobe = total ? toLobe + s : glm::max(toLobe, s);
}

}  // namespace

bool CutWorkspace::Foldable::operator<(const Foldable& o) const {
  return key < o.key || (key == o.key && item < o.item);
}

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
                      float(colour_.slackFloor), rule.total, rule.walkBounds},
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
    cut.farRemainders = seed->farRemainders;
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
  // A seed's cut this far off under the total rule is no seed: its quarters start from the
  // roots. Its entries are written instead, for its own pixels (cut_frame.cpp's cutSquare).
  emit(cut, entries, cut.result.full ? nullptr : next);
  return cut.result;
}

bool TileCutter::refine(Cut& cut) const {
  using Item = CutWorkspace::Item;
  std::vector<std::uint64_t>& heap = cut.work.heap;
  const CutRule& rule = cut.rule;
  while (!heap.empty()) {
    const float top = cut.topOfHeap();
    if (cut.holds(cut.margin(), top, cut.errorSum)) break;
    const int size = int(heap.size() + cut.work.settled.size()) + cut.far.count();
    if (cut.full(size, top)) {
      // At the finest size, a full cut that meets the rule at the centre without the margin
      // is still shared: its pixels check it for themselves, and most pass (where a surface
      // meets another, 4×4 squares fill up just above the margin's target, and per-pixel
      // cuts there would be far larger).
      // Larger groups split instead: the quarters' cuts are smaller, and so cheaper per pixel.
      if (cut.finest && cut.holds(1.0f, top, cut.errorSum)) break;
      const float want = cut.target(cut.margin(), cut.errorSum);
      const float have = rule.total ? maxOf(cut.errorSum) : top;
      cut.result.shortfall = want > 0.0f ? have / want : std::numeric_limits<float>::infinity();
      if (rule.total && rule.shareFull && cut.sharedFull(top)) {
        if (!cut.wantSeed) {
          cut.result.full = true;
          break;
        }
        // A seed this far off: its quarters would fill up too. cut_frame.cpp's cutSquare gives
        // its pixels an exact cut at once where it may, else this full cut.
        cut.result.exact = rule.exactFull;
        cut.result.full = !rule.exactFull;
      }
      cut.result.perPixel = true;  // the tile's cut is full: its pixels cut for themselves
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
             !cut.holds(cut.margin(), cut.topOfHeap(), errorLeft) &&
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
  const SpecularLobes& lobes = cut.terms.g.lobes;
  FoldLanes& lights = work.lights;
  work.shape.assign(work.items.size(), -1.0f);
  int batch[kLanes], batchCount = 0;
  auto foldBatch = [&]() MANYLIGHT_INLINE {
    float t[kLanes];
    foldBounds(cut.terms, lights, batchCount, t);
    for (int b = 0; b < batchCount; ++b) {
      if (t[b] >= 0.0f) {
        const CutWorkspace::Item& it = work.items[std::size_t(batch[b])];
        const glm::vec3 tb = it.intensity * t[b];
        const float key =
            !rule.total && lobes.on ? maxOf(lobes.specular * it.lobeSpread) : maxOf(tb);
        work.foldable.push_back({batch[b], tb, key});
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
    // target; the entries with the least spread fold first. Their remainders T err together
    // where the entries lie the same way from the group (many lights at one point, all of
    // one sign): the far field's entries in each bin of directions (farBin) count as one
    // node, their summed T within the target.
    if (lobes.on) std::sort(work.foldable.begin(), work.foldable.end());
    const float target = kMargin * rule.error * maxOf(cut.sum);
    for (const Foldable& f : work.foldable) {
      const CutWorkspace::Item& it = work.items[std::size_t(f.item)];
      const glm::vec3 b = it.error + f.t;
      const glm::vec3 w = lobes.on ? weigh(lobes, b, it.lobeError) : b;
      if (maxOf(w) > target) continue;
      const Node& n = node(it.tree, it.index);
      glm::vec3& binSum =
          cut.farRemainders[farBin(it.tree == 0 ? n.repPoint : n.repPoint - cut.terms.centre)];
      const glm::vec3 remainder = binSum + f.t;
      if (maxOf(lobes.on ? lobes.albedo * remainder : remainder) > target) continue;
      const glm::vec3 spread = cut.farLobeSpread + it.lobeSpread;
      if (lobes.on && maxOf(lobes.specular * spread) > kLobeFold * target) break;
      join(false, result.check, result.lobeCheck, b, it.lobeError);
      join(false, cut.farCheck, cut.farLobeCheck, b, it.lobeError);
      cut.farLobeSpread = spread;
      binSum = remainder;
      work.shape[std::size_t(f.item)] = kFolded;
    }
    result.lobeCheck = glm::max(result.lobeCheck, cut.farLobeSpread);
    for (const glm::vec3& binSum : cut.farRemainders) result.check = glm::max(result.check, binSum);
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
    next->farRemainders = cut.farRemainders;
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
