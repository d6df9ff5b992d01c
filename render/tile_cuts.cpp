#include "render/tile_cuts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "bake/light_tree_layout.h"
#include "render/cpu_clones.h"
#include "render/cut_heap.h"
#include "render/far_field.h"
#include "render/region_bounds.h"
#include "render/threads.h"

namespace manylight {

using namespace region_bounds;

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kMinDistanceSquared = 1e-12f;  // glsl/shading.glsl
constexpr float kAbsoluteFloor = 1e-6f;        // glsl/lighting_lightcuts.frag
// The CPU stops refining once the rule holds against its estimate at the tile's centre
// times this margin, so that most pixels, whose estimates differ from the centre's, pass
// their own check.
constexpr float kMargin = 0.5f;
// Under the total rule, a square whose cut filled up is split into quarters only if the
// cut's summed bound was within this factor of the rule's target.
constexpr float kSplitShortfall = 8.0f;
// Under the total rule, entries fold into the far field while the summed bound stays within
// this share of the rule's target (the cut itself stopped at kMargin).
constexpr float kFoldMargin = 0.75f;
// Under the node rule, a cut past half the maximum whose largest bound is still this many
// times the target is given up as full: refining the rest would fill it anyway (on 65,536
// mixed, uniform and clustered lights the cuts and images are the same as without, and
// 6% fewer bounds are evaluated).
constexpr float kHopeless = 4.0f;

float maxOf(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

}  // namespace

std::size_t RegionCut::entryTexels() const {
  return std::size_t(2 * (counts[0] + counts[1]) + 3 * counts[2] +
                     (folded > 0 ? kFarFieldTexels : 0));
}

void RegionCut::writeHeader(std::uint32_t firstEntryTexel, std::uint32_t* words) const {
  const std::uint32_t header[8] = {firstEntryTexel,          std::uint32_t(counts[0]),
                                   std::uint32_t(counts[1]), std::uint32_t(counts[2]),
                                   layout::wordOf(check.x),  layout::wordOf(check.y),
                                   layout::wordOf(check.z),  std::uint32_t(folded)};
  std::copy_n(header, 8, words);
}

TileCuts TileCutter::cut(const GBufferPixels& px, int tileSize, const CutRule& rule, int threads,
                         const std::vector<std::uint8_t>* only) const {
  TileCuts out;
  const int fine = std::min(kFinestTile, tileSize);
  out.cutOfPixel.assign(std::size_t(px.width) * px.height, kNoSharedCut);
  // Squares of `top` pixels find seed cuts for their quarters, down to squares of tileSize.
  const int top = tileSize << kSeedLevels;
  const int coarseX = (px.width + top - 1) / top;
  const int coarse = coarseX * ((px.height + top - 1) / top);
  threads = std::clamp(threads, 1, std::max(coarse, 1));

  // Per thread: its cuts (numbered in order; cutOfPixel holds these numbers until the merge)
  // and their entries.
  struct Part {
    std::vector<RegionCut> cuts;
    std::vector<std::size_t> entry;  // each cut's first word in `entries`
    std::vector<std::uint32_t> entries;
    long long bounds = 0;  // split groups' too
    int perPixel = 0, splits = 0;
  };
  std::vector<Part> parts(static_cast<std::size_t>(threads));

  // A group of a square's covered pixels (indices y · width + x), and the seed its cut
  // starts from.
  struct Group {
    int x0, y0, size;
    std::vector<int> pixels;
    std::shared_ptr<const CutSeed> seed;
  };
  auto quarters = [&](Group& group, std::vector<Group>& todo,
                      const std::shared_ptr<const CutSeed>& seed) {
    const int h = group.size / 2;
    Group quarter[4];
    for (int q = 0; q < 4; ++q)
      quarter[q] = {group.x0 + (q & 1) * h, group.y0 + (q >> 1) * h, h, {}, seed};
    for (const int i : group.pixels) {
      const int x = i % px.width, y = i / px.width;
      quarter[(x >= group.x0 + h ? 1 : 0) + (y >= group.y0 + h ? 2 : 0)].pixels.push_back(i);
    }
    for (Group& q : quarter) {
      if (!q.pixels.empty()) todo.push_back(std::move(q));
    }
  };
  // Squares are dealt out round robin: square t is part partOf(t)'s. The merge below
  // renumbers each pixel's cut by its square's part.
  auto partOf = [&](int t) { return t % threads; };
  auto work = [&](int index) {
    Part& part = parts[std::size_t(index)];
    std::vector<Group> todo;
    std::vector<std::uint32_t> unused;
    for (int t = 0; t < coarse; ++t) {
      if (partOf(t) != index) continue;
      Group first{(t % coarseX) * top, (t / coarseX) * top, top, {}, nullptr};
      for (int y = first.y0; y < std::min(first.y0 + top, px.height); ++y) {
        for (int x = first.x0; x < std::min(first.x0 + top, px.width); ++x) {
          const std::size_t i = std::size_t(y) * px.width + x;
          if ((!only || (*only)[i]) && sharesCuts(px, i)) first.pixels.push_back(int(i));
        }
      }
      if (!first.pixels.empty()) todo.push_back(std::move(first));
      while (!todo.empty()) {
        Group group = std::move(todo.back());
        todo.pop_back();
        ShadingRegion g;
        const bool cone = shadingRegion(px, group.pixels, g);
        // Normals over 90° apart leave no cosine bound: split without trying.
        const bool tried = cone && g.cosSpread >= 0.0f;
        if (group.size > tileSize) {  // a seed for the quarters
          if (tried) {
            auto next = std::make_shared<CutSeed>();
            const RegionCut r = cutRegion(g, rule, false, unused, group.seed.get(), next.get());
            part.bounds += r.bounds;
            // A full cut is a start too: a quarter whose cut then fills up starts over below.
            quarters(group, todo, next);
            continue;
          }
          Group a{group.x0, group.y0, group.size, {}, group.seed}, b = a;
          if (splitByNormal(px, group.pixels, g, a.pixels, b.pixels)) {
            todo.push_back(std::move(a));
            todo.push_back(std::move(b));
          } else {
            quarters(group, todo, group.seed);
          }
          continue;
        }
        RegionCut result;
        const std::size_t entry = part.entries.size();
        if (tried) {
          result = cutRegion(g, rule, group.size <= fine, part.entries, group.seed.get());
          part.bounds += result.bounds;
          if (result.perPixel && group.seed) {  // the seed's cut was too fine here: start over
            group.seed = nullptr;
            result = cutRegion(g, rule, group.size <= fine, part.entries);
            part.bounds += result.bounds;
          }
        }
        if (tried && !result.perPixel) {
          for (const int i : group.pixels)
            out.cutOfPixel[std::size_t(i)] = std::uint32_t(part.cuts.size());
          part.cuts.push_back(result);
          part.entry.push_back(entry);
          continue;
        }
        part.entries.resize(entry);
        Group a{group.x0, group.y0, group.size, {}, group.seed}, b = a;
        if ((!cone || g.cosSpread < kSurfaceSpread) &&
            splitByNormal(px, group.pixels, g, a.pixels, b.pixels)) {
          ++part.splits;
          todo.push_back(std::move(a));
          todo.push_back(std::move(b));
          continue;
        }
        // Smaller squares have tighter bounds: try the quarters. Under the total rule, a cut
        // that filled up far from its target fills up in the quarters too (its bounds add up
        // over the whole cut); under the node rule the culprit is mostly a light near one
        // corner, which a quarter leaves out.
        if (cone && group.size > fine && (!rule.total || result.shortfall < kSplitShortfall)) {
          quarters(group, todo, group.seed);
          continue;
        }
        ++part.perPixel;
      }
    }
  };
  onThreads(threads, work);

  // Number the cuts part after part, and lay out headers, then entries.
  std::vector<std::uint32_t> firstCut(parts.size(), 0);
  std::size_t cuts = 0, entryTexels = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    firstCut[k] = std::uint32_t(cuts);
    cuts += parts[k].cuts.size();
    entryTexels += parts[k].entries.size() / 4;
    out.boundEvaluations += parts[k].bounds;
    out.perPixelGroups += parts[k].perPixel;
    out.surfaceSplits += parts[k].splits;
  }
  out.sharedCuts = int(cuts);
  out.made = out.sharedCuts + out.perPixelGroups;
  for (std::size_t i = 0; i < out.cutOfPixel.size(); ++i) {
    std::uint32_t& c = out.cutOfPixel[i];
    if (c == kNoSharedCut) continue;
    const int x = int(i % std::size_t(px.width)), y = int(i / std::size_t(px.width));
    c += firstCut[std::size_t(partOf((y / top) * coarseX + x / top))];
  }
  out.texels.assign((2 * cuts + entryTexels) * 4, 0u);
  std::size_t next = 2 * cuts;
  std::uint32_t* head = out.texels.data();
  for (const Part& part : parts) {
    for (std::size_t k = 0; k < part.cuts.size(); ++k, head += 8) {
      const RegionCut& r = part.cuts[k];
      r.writeHeader(std::uint32_t(next), head);
      const std::size_t texels = r.entryTexels();
      std::copy_n(part.entries.data() + part.entry[k], texels * 4, out.texels.data() + next * 4);
      next += texels;
    }
  }
  return out;
}

// The cut loop runs in a copy for AVX2 where the CPU has it (render/cpu_clones.h): 65,536
// mixed lights at 640x480, 160 against 142 ms.
MANYLIGHT_AVX2_CLONES
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

  // The smallest cosine between a normal of the region and a vector of the box [dMin, dMax],
  // whose farthest length is dFar and bounding sphere's lower cosine sphereLower.
  auto lowestCosine = [&](glm::vec3 dMin, glm::vec3 dMax, float dFar,
                          float sphereLower) MANYLIGHT_INLINE {
    return widenDown(std::max(cosineLower(g.axis, dMin, dMax, dFar), sphereLower), g.cosSpread,
                     g.sinSpread);
  };
  // The representative's shading at the centre per unit albedo and intensity.
  auto unitEstimate = [&](int tree, const Node& n) MANYLIGHT_INLINE {
    float e;
    if (tree == 0) {
      e = std::max(glm::dot(g.axis, n.repPoint), 0.0f);
    } else {
      const glm::vec3 v = n.repPoint - centre;
      const float d2 = std::max(glm::dot(v, v), kMinDistanceSquared);
      const glm::vec3 dir = v / std::sqrt(d2);
      e = std::max(glm::dot(g.axis, dir), 0.0f) * window(d2, n.repInvRange2) / d2;
      if (tree == 2 && glm::dot(n.repAxis, -dir) < n.repCos) e = 0.0f;
    }
    return e / kPi;
  };

  // A node's item; a child shares its parent's representative half of the time, and then
  // its shading at the centre.
  auto makeItem = [&](int tree, int i, const Item* parent) MANYLIGHT_INLINE {
    const Node& n = node(tree, i);
    Item it{-1.0f, tree,       i, glm::vec3(0.0f), glm::vec3(0.0f), true, n.leaf, n.representative,
            0.0f,  n.intensity};
    if (n.representative < 0) return it;
    it.unit =
        parent && parent->representative == n.representative ? parent->unit : unitEstimate(tree, n);
    it.estimate = n.intensity * it.unit;
    ++result.bounds;
    glm::vec3 dMin = n.boxMin, dMax = n.boxMax;
    if (tree != 0) {
      dMin = n.boxMin - g.pMax;
      dMax = n.boxMax - g.pMin;
    }
    const glm::vec2 d2 = lengths2(dMin, dMax);
    const float d2Min = d2.x, d2Max = d2.y;
    it.dark = false;
    if (tree != 0 && d2Min == 0.0f) {
      if (!n.leaf) it.measure = std::numeric_limits<float>::infinity();
      return it;
    }
    const float dist = std::sqrt(d2Min);
    const glm::vec2 sphere = sphereCosines(g.axis, dMin, dMax);
    const float cosUp = widenUp(std::min(cosineUpper(g.axis, dMin, dMax, dist), sphere.x),
                                g.cosSpread, g.sinSpread);
    glm::vec3 upper(0.0f), lower(0.0f);
    const bool reaches =
        tree != 2 || spotMayReach(n.boxMin, n.boxMax, n.axis, n.w2, n.sinTheta, g.pMin, g.pMax);
    if (cosUp > 0.0f && reaches) {
      float gUp = 1.0f, gLow = 1.0f;
      if (tree != 0) {
        gUp = window(d2Min, n.invRange2) / std::max(d2Min, kMinDistanceSquared);
        gLow = tree == 2 ? 0.0f : window(d2Max, n.w2) / std::max(d2Max, kMinDistanceSquared);
      }
      const float slack = slackRate * maxOf(n.intensity) + slackFloor;
      upper = (n.intensity + slack) * (cosUp * gUp / kPi);
      if (!std::isfinite(maxOf(upper))) {
        if (!n.leaf) it.measure = std::numeric_limits<float>::infinity();
        return it;
      }
      if (rule.total && gLow > 0.0f) {
        const float cosLow = lowestCosine(dMin, dMax, std::sqrt(d2Max), sphere.y);
        lower = glm::max(n.intensity - slack, glm::vec3(0.0f)) * (cosLow * gLow / kPi);
      }
    }
    it.dark = maxOf(upper) <= 0.0f;
    if (n.leaf) return it;  // exact: never refined, no error
    it.error = rule.total ? upper - lower : upper;
    it.measure = maxOf(it.error);
    return it;
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
  // The far field the cut starts from (a seed's, about this group's centre), and the bound of
  // the entries folded into it.
  FarField far(centre);
  glm::vec3 farCheck(0.0f);
  if (seed) {
    far = seed->far.movedTo(centre);
    farCheck = seed->farCheck;
    sum += far.irradianceAtCentre(g.axis) / kPi;
    if (rule.total) errorSum += farCheck;
    for (const CutSeed::NodeRef& n : seed->nodes) add(makeItem(n.tree, n.index, nullptr));
  } else {
    for (int t = 0; t < 3; ++t) {
      if (leaves_[t] > 0) add(makeItem(t, 0, nullptr));
    }
  }
  while (!heap.empty()) {
    const float top = layout::floatOf(std::uint32_t(heap.front() >> 32));
    // The rule's measure of the cut (its largest bound, or under the total rule their sum)
    // and whether it meets the rule's target at the centre times `margin`.
    const float have = rule.total ? maxOf(errorSum) : top;
    auto target = [&](float margin) {
      return margin * rule.error * maxOf(rule.total ? sum - errorSum : sum);
    };
    auto holds = [&](float margin) {
      return std::isfinite(top) &&
             (have <= target(margin) || (rule.total && have <= kAbsoluteFloor));
    };
    if (holds(kMargin)) break;
    const int size = int(heap.size() + settled.size()) + far.count();
    if (size + 1 > rule.maxCut || (!rule.total && 2 * size > rule.maxCut &&
                                   top > kHopeless * kMargin * rule.error * maxOf(sum))) {
      // At the finest size, a full cut that meets the rule at the centre without the margin
      // is still shared: its pixels check it for themselves, and most pass (where a surface
      // meets another, 4×4 squares of 65,536 mixed lights filled up 1.0–1.5× above the
      // margin's target, and their pixels walked cuts of their own, 4,000 node bounds each).
      // Larger groups split instead: the quarters' cuts are smaller, and so cheaper per pixel.
      if (finest && holds(1.0f)) break;
      result.perPixel = true;  // the tile's cut is full: its pixels cut for themselves
      const float want = target(kMargin);
      result.shortfall = want > 0.0f ? have / want : std::numeric_limits<float>::infinity();
      if (!next) return result;
      break;  // still a seed
    }
    cut_heap::popHeap(heap);
    const Item parent = items[std::size_t(heap.back() & 0xffffffffu)];
    heap.pop_back();
    sum -= parent.estimate;
    if (std::isfinite(parent.measure)) errorSum -= parent.error;
    add(makeItem(parent.tree, 2 * parent.index + 1, &parent));
    add(makeItem(parent.tree, 2 * parent.index + 2, &parent));
  }
  for (const std::uint64_t e : heap) settled.push_back(int(e & 0xffffffffu));

  // The far field: directional, point and spot entries lighting every pixel of the tile from in
  // front, folded into one linear function while the rule keeps a margin (far_field.h).
  // Under the node rule an entry folds when its bound plus T stays within the margin the
  // cut stopped at; under the total rule the smallest T fold first while the summed bound
  // stays within kFoldMargin of the rule.
  const float h2 = 0.25f * glm::dot(g.pMax - g.pMin, g.pMax - g.pMin);
  struct Foldable {
    int item;
    glm::vec3 t;                               // T per channel
    bool operator<(const Foldable& o) const {  // smallest T first
      return std::make_pair(maxOf(t), item) < std::make_pair(maxOf(o.t), o.item);
    }
  };
  thread_local std::vector<Foldable> foldable;
  foldable.clear();
  for (const int k : settled) {
    const Item& it = items[std::size_t(k)];
    if (it.dark) continue;
    if (!it.leaf)
      result.check = rule.total ? result.check + it.error : glm::max(result.check, it.error);
    const Node& l = node(it.tree, it.index);  // its representative's light: l.rep…
    // A spot folds with its cone, at a T that grows with how much the cone varies over the
    // tile (none where it lets all its light through, or none, to the whole tile).
    ConeVariation variation;
    if (it.tree == 2) {
      if (!std::isfinite(l.repConeScale)) continue;  // a hard edge: not smooth
      variation = coneVariation(l.repConeScale, l.repConeOffset, l.repCos,
                                axisCosines(l.repAxis, l.repPoint, g.pMin, g.pMax));
    }
    float t = 0.0f;
    if (it.tree == 0) {
      if (widenDown(glm::dot(g.axis, l.repPoint), g.cosSpread, g.sinSpread) <= 0.0f) continue;
    } else {
      const glm::vec3 dMin = l.repPoint - g.pMax, dMax = l.repPoint - g.pMin;
      const glm::vec2 d2 = lengths2(dMin, dMax);
      if (d2.x <= 0.0f ||
          lowestCosine(dMin, dMax, std::sqrt(d2.y), sphereCosines(g.axis, dMin, dMax).y) <= 0.0f)
        continue;
      t = float(linearisationBound(d2.x, l.repInvRange2, h2, it.tree == 2 ? &variation : nullptr));
    }
    foldable.push_back({k, it.intensity * t});
  }
  thread_local std::vector<bool> folded;
  folded.assign(items.size(), false);
  result.check = rule.total ? result.check + farCheck : glm::max(result.check, farCheck);
  if (rule.total) {
    std::sort(foldable.begin(), foldable.end());
    for (const Foldable& f : foldable) {
      const glm::vec3 b = result.check + f.t;
      if (maxOf(b) > kFoldMargin * rule.error * maxOf(sum - b)) break;
      result.check = b;
      farCheck += f.t + items[std::size_t(f.item)].error;
      folded[std::size_t(f.item)] = true;
    }
  } else {
    for (const Foldable& f : foldable) {
      const glm::vec3 b = items[std::size_t(f.item)].error + f.t;
      if (maxOf(b) > kMargin * rule.error * maxOf(sum)) continue;
      result.check = glm::max(result.check, b);
      farCheck = glm::max(farCheck, b);
      folded[std::size_t(f.item)] = true;
    }
  }

  // The cut's entries: the far field first, then tree by tree (the bounds are set above).
  if (next) next->nodes.clear();
  thread_local std::vector<std::uint32_t> byTree[3];
  for (auto& e : byTree) e.clear();
  for (const int k : settled) {
    const Item& it = items[std::size_t(k)];
    if (it.dark) continue;  // contributes nothing anywhere in the tile
    const Node& l = node(it.tree, it.index);
    if (folded[std::size_t(k)]) {
      if (it.tree == 0) {
        far.addDirectional(l.repPoint, it.intensity);
      } else if (it.tree == 2) {
        far.addSpot(l.repPoint, l.repInvRange2, {l.repAxis, l.repConeScale, l.repConeOffset},
                    it.intensity);
      } else {
        far.addPoint(l.repPoint, l.repInvRange2, it.intensity);
      }
      continue;
    }
    if (next) {
      next->nodes.push_back({it.tree, it.index});
      continue;
    }
    // The representative itself: direction or position, and 1/range²; a spot's cone; the
    // node's intensity.
    std::vector<std::uint32_t>& e = byTree[it.tree];
    for (const float w :
         {l.repPoint.x, l.repPoint.y, l.repPoint.z, it.tree == 0 ? 0.0f : l.repInvRange2})
      e.push_back(layout::wordOf(w));
    float coneOffset = 0.0f;
    if (it.tree == 2) {
      for (const float w : {l.repAxis.x, l.repAxis.y, l.repAxis.z, l.repConeScale})
        e.push_back(layout::wordOf(w));
      coneOffset = l.repConeOffset;
    }
    for (const float w : {it.intensity.x, it.intensity.y, it.intensity.z, coneOffset})
      e.push_back(layout::wordOf(w));
  }
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
