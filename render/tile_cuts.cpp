#include "render/tile_cuts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "bake/light_pack.h"
#include "bake/light_tree_layout.h"
#include "render/far_field.h"
#include "render/region_bounds.h"

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

float bitsToFloat(std::uint32_t w) {
  float f;
  std::memcpy(&f, &w, 4);
  return f;
}

std::uint32_t floatToBits(float f) {
  std::uint32_t w;
  std::memcpy(&w, &f, 4);
  return w;
}

float maxOf(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

}  // namespace

// The tile's shading points: their box, and a cone around `axis` holding their normals.
struct TileCutter::Region {
  glm::vec3 pMin, pMax, axis;
  float cosSpread, sinSpread;
};

struct TileCutter::Result {
  int counts[3] = {0, 0, 0};  // entries per tree, besides the far field
  int folded = 0;             // entries in the far field
  glm::vec3 check{0.0f};
  bool perPixel = false;
  long long bounds = 0;
  float shortfall = 0.0f;  // a full cut: how far its measure was above the rule's target
};

TileCutter::TileCutter(const PackedTrees& packed, const std::vector<Light>& lights)
    : colour_(packed.colour) {
  const LightOrder order = lightOrder(lights);  // the light texture's slots
  spotStart_ = order.spotStart;
  for (std::size_t slot = std::size_t(order.spotStart); slot < lights.size(); ++slot) {
    const Light& l = lights[std::size_t(order.scene[slot])];
    const SpotConeTerms terms = spotConeTerms(l);
    spotCones_.push_back({l.direction, terms.scale, terms.offset});
  }
  int slots = 0;
  for (int t = 0; t < 3; ++t) {
    leaves_[t] = packed.leaves[t];
    const int count = leaves_[t] > 0 ? 2 * leaves_[t] - 1 : 0;
    nodes_[t].reserve(std::size_t(count));
    for (int i = 0; i < count; ++i) nodes_[t].push_back(decode(packed, t, i));
    for (int i = leaves_[t] - 1; i < 2 * leaves_[t] - 1; ++i) {
      slots = std::max(slots, node(t, i).representative + 1);
    }
  }
  leafOfSlot_.assign(std::size_t(slots), -1);
  for (int t = 0; t < 3; ++t) {
    for (int i = leaves_[t] - 1; i < 2 * leaves_[t] - 1; ++i) {
      const int slot = node(t, i).representative;
      if (slot >= 0) leafOfSlot_[std::size_t(slot)] = i;
    }
  }
}

TileCutter::Node TileCutter::decode(const PackedTrees& packed, int tree, int i) {
  const std::uint32_t* w = packed.words.data() + packed.base[tree] +
                           std::size_t(tree == 2 ? layout::kSpotNodeWords : layout::kNodeWords) * i;
  Node n;
  n.boxMin = {bitsToFloat(w[0]), bitsToFloat(w[1]), bitsToFloat(w[2])};
  n.representative = int(w[3]);
  n.invRange2 = bitsToFloat(w[7]);
  n.leaf = i >= packed.leaves[tree] - 1;
  const glm::vec3 words46{bitsToFloat(w[4]), bitsToFloat(w[5]), bitsToFloat(w[6])};
  n.boxMax = n.leaf ? n.boxMin : words46;
  n.intensity = n.leaf ? words46 : packed.colour.decode(w[8]);
  n.w2 = bitsToFloat(w[9]);
  if (tree == 2) {
    n.axis = {bitsToFloat(w[10]), bitsToFloat(w[11]), bitsToFloat(w[12])};
    n.sinTheta = bitsToFloat(w[13]);
  }
  return n;
}

// The region of the pixels [x0, x1) × [y0, y1); false when no pixel is covered. `perPixel`:
// some pixel is specular (its bounds are not per unit albedo), or the normals cancel out.
bool TileCutter::region(const GBufferPixels& px, int x0, int y0, int x1, int y1, Region& g,
                        bool& perPixel) {
  g = Region{glm::vec3(std::numeric_limits<float>::max()),
             glm::vec3(-std::numeric_limits<float>::max()), glm::vec3(0.0f), 1.0f, 0.0f};
  int covered = 0;
  bool specular = false;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t i = (std::size_t(y) * px.width + x) * 4;
      if (px.normal[i + 3] == 0.0f) continue;
      ++covered;
      const glm::vec3 p{px.position[i], px.position[i + 1], px.position[i + 2]};
      g.pMin = glm::min(g.pMin, p);
      g.pMax = glm::max(g.pMax, p);
      g.axis += glm::vec3{px.normal[i], px.normal[i + 1], px.normal[i + 2]};
      specular = specular || px.specular[i] != 0.0f || px.specular[i + 1] != 0.0f ||
                 px.specular[i + 2] != 0.0f;
    }
  }
  if (covered == 0) return false;
  const float len = glm::length(g.axis);
  if (len > 0.0f) g.axis /= len;
  for (int y = y0; y < y1 && len > 0.0f; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t i = (std::size_t(y) * px.width + x) * 4;
      if (px.normal[i + 3] == 0.0f) continue;
      const glm::vec3 n{px.normal[i], px.normal[i + 1], px.normal[i + 2]};
      g.cosSpread = std::min(g.cosSpread, glm::dot(n, g.axis) / std::max(glm::length(n), 1e-20f));
    }
  }
  // Round-off: a flat tile's normals differ in their last bits.
  g.cosSpread = std::max(g.cosSpread - 1e-6f, -1.0f);
  g.sinSpread = std::sqrt(std::max(1.0f - g.cosSpread * g.cosSpread, 0.0f));
  perPixel = specular || len == 0.0f;
  return true;
}

TileCuts TileCutter::cut(const GBufferPixels& px, int tileSize, const CutRule& rule,
                         int threads) const {
  TileCuts out;
  const int fine = std::min(kFinestTile, tileSize);
  out.tileSize = fine;
  out.tilesX = (px.width + fine - 1) / fine;
  out.tilesY = (px.height + fine - 1) / fine;
  const int coarseX = (px.width + tileSize - 1) / tileSize;
  const int coarse = coarseX * ((px.height + tileSize - 1) / tileSize);
  threads = std::clamp(threads, 1, std::max(coarse, 1));

  // A square of the quadtree that got a shared cut, or is left to per-pixel cuts.
  struct Square {
    int x0, y0, size;  // pixels
    Result result;
    std::size_t entry;  // its first word in the thread's entries
  };
  std::vector<std::vector<Square>> squares(static_cast<std::size_t>(threads));
  std::vector<std::vector<std::uint32_t>> entries(static_cast<std::size_t>(threads));
  std::vector<long long> bounds(static_cast<std::size_t>(threads), 0);  // split squares' too

  auto work = [&](int part) {
    std::vector<std::uint32_t>& mine = entries[std::size_t(part)];
    std::vector<Square>& done = squares[std::size_t(part)];
    std::vector<std::array<int, 3>> todo;
    for (int t = part; t < coarse; t += threads) {
      todo.push_back({(t % coarseX) * tileSize, (t / coarseX) * tileSize, tileSize});
      while (!todo.empty()) {
        const auto [x0, y0, size] = todo.back();
        todo.pop_back();
        Region g;
        bool perPixel = false;
        if (!region(px, x0, y0, std::min(x0 + size, px.width), std::min(y0 + size, px.height), g,
                    perPixel)) {
          continue;
        }
        Square sq{x0, y0, size, Result{}, mine.size()};
        if (!perPixel) sq.result = cutTile(g, rule, mine);
        sq.result.perPixel = sq.result.perPixel || perPixel;
        bounds[std::size_t(part)] += sq.result.bounds;
        // Under the total rule, a cut that filled up far from its target fills up in the
        // quarters too (its bounds add up over the whole cut); under the node rule the
        // culprit is mostly a light near one corner, which a quarter leaves out.
        if (sq.result.perPixel && size > fine &&
            (!rule.total || sq.result.shortfall < kSplitShortfall)) {
          // Smaller squares have tighter bounds: try the four quarters.
          mine.resize(sq.entry);
          const int h = size / 2;
          for (int q = 0; q < 4; ++q) {
            if (x0 + (q & 1) * h < px.width && y0 + (q >> 1) * h < px.height) {
              todo.push_back({x0 + (q & 1) * h, y0 + (q >> 1) * h, h});
            }
          }
          continue;
        }
        if (sq.result.perPixel) mine.resize(sq.entry);
        done.push_back(sq);
      }
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (int part = 0; part < threads; ++part) pool.emplace_back(work, part);
    for (std::thread& th : pool) th.join();
  }

  const std::size_t tiles = std::size_t(out.tilesX) * out.tilesY;
  std::size_t entryTexels = 0;
  for (const auto& e : entries) entryTexels += e.size() / 4;
  out.texels.assign((2 * tiles + entryTexels) * 4, 0u);
  std::size_t next = 2 * tiles;
  for (int part = 0; part < threads; ++part) {
    out.boundEvaluations += bounds[std::size_t(part)];
    for (const Square& sq : squares[std::size_t(part)]) {
      const Result& r = sq.result;
      r.perPixel ? ++out.perPixelTiles : ++out.sharedTiles;
      std::uint32_t head[8] = {std::uint32_t(next),
                               std::uint32_t(r.counts[0]),
                               std::uint32_t(r.counts[1]),
                               std::uint32_t(r.counts[2]),
                               floatToBits(r.check.x),
                               floatToBits(r.check.y),
                               floatToBits(r.check.z),
                               (r.perPixel ? kTilePerPixel : 0u) | std::uint32_t(r.folded)
                                                                       << kTileFoldedShift};
      for (int ty = sq.y0 / fine; ty < std::min((sq.y0 + sq.size) / fine, out.tilesY); ++ty) {
        for (int tx = sq.x0 / fine; tx < std::min((sq.x0 + sq.size) / fine, out.tilesX); ++tx) {
          std::copy_n(head, 8, out.texels.data() + (std::size_t(ty) * out.tilesX + tx) * 8);
        }
      }
      if (r.perPixel) continue;
      const std::vector<std::uint32_t>& src = entries[std::size_t(part)];
      const std::size_t texels = std::size_t(2 * (r.counts[0] + r.counts[1]) + 3 * r.counts[2] +
                                             (r.folded > 0 ? kFarFieldTexels : 0));
      std::copy_n(src.data() + sq.entry, texels * 4, out.texels.data() + next * 4);
      next += texels;
    }
  }
  return out;
}

TileCutter::Result TileCutter::cutTile(const Region& g, const CutRule& rule,
                                       std::vector<std::uint32_t>& entries) const {
  Result result;
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
  auto lowestCosine = [&](glm::vec3 dMin, glm::vec3 dMax, float dFar, float sphereLower) {
    return widenDown(std::max(cosineLower(g.axis, dMin, dMax, dFar), sphereLower), g.cosSpread,
                     g.sinSpread);
  };
  // The representative's shading at the centre per unit albedo and intensity.
  auto unitEstimate = [&](int tree, const Node& n) {
    const int leaf = leafOfSlot_[std::size_t(n.representative)];
    const Node& l = node(tree, leaf);
    float e;
    if (tree == 0) {
      e = std::max(glm::dot(g.axis, l.boxMin), 0.0f);
    } else {
      const glm::vec3 v = l.boxMin - centre;
      const float d2 = std::max(glm::dot(v, v), kMinDistanceSquared);
      const glm::vec3 dir = v / std::sqrt(d2);
      e = std::max(glm::dot(g.axis, dir), 0.0f) * window(d2, l.invRange2) / d2;
      if (tree == 2 && glm::dot(l.axis, -dir) < l.w2) e = 0.0f;
    }
    return e / kPi;
  };

  // A node's item; a child shares its parent's representative half of the time, and then
  // its shading at the centre.
  auto makeItem = [&](int tree, int i, const Item* parent) {
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
  // others by measure, as (measure, item) pairs.
  // Kept per thread between tiles: allocating them per tile costs more than the cut.
  thread_local std::vector<Item> items;
  thread_local std::vector<int> settled;
  thread_local std::vector<std::pair<float, int>> heap;
  items.clear();
  settled.clear();
  heap.clear();
  glm::vec3 sum(0.0f), errorSum(0.0f);
  auto add = [&](const Item& it) {
    if (it.representative < 0) return;  // empty: holds no light
    sum += it.estimate;
    if (it.measure > 0.0f && std::isfinite(it.measure)) errorSum += it.error;
    items.push_back(it);
    const int k = int(items.size()) - 1;
    if (it.measure > 0.0f) {
      heap.emplace_back(it.measure, k);
      std::push_heap(heap.begin(), heap.end());
    } else {
      settled.push_back(k);
    }
  };
  for (int t = 0; t < 3; ++t) {
    if (leaves_[t] > 0) add(makeItem(t, 0, nullptr));
  }
  while (!heap.empty()) {
    const float top = heap.front().first;
    if (std::isfinite(top)) {
      const bool holds = rule.total
                             ? (maxOf(errorSum) <= kMargin * rule.error * maxOf(sum - errorSum) ||
                                maxOf(errorSum) <= kAbsoluteFloor)
                             : top <= kMargin * rule.error * maxOf(sum);
      if (holds) break;
    }
    if (int(heap.size() + settled.size()) + 1 > rule.maxCut) {
      result.perPixel = true;  // the tile's cut is full: its pixels cut for themselves
      const float have = rule.total ? maxOf(errorSum) : top;
      const float want = kMargin * rule.error * maxOf(rule.total ? sum - errorSum : sum);
      result.shortfall = want > 0.0f ? have / want : std::numeric_limits<float>::infinity();
      return result;
    }
    std::pop_heap(heap.begin(), heap.end());
    const Item parent = items[std::size_t(heap.back().second)];
    heap.pop_back();
    sum -= parent.estimate;
    if (std::isfinite(parent.measure)) errorSum -= parent.error;
    add(makeItem(parent.tree, 2 * parent.index + 1, &parent));
    add(makeItem(parent.tree, 2 * parent.index + 2, &parent));
  }
  for (const auto& [measure, k] : heap) settled.push_back(k);

  // The far field: directional and point entries lighting every pixel of the tile from in
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
    const Node& l = node(it.tree, leafOfSlot_[std::size_t(it.representative)]);
    if (it.tree == 2) {
      const SpotCone& cone = spotCone(it.representative);
      if (!spotFullOver(cone.axis, cone.scale, cone.offset, l.boxMin, g.pMin, g.pMax)) continue;
    }
    float t = 0.0f;
    if (it.tree == 0) {
      if (widenDown(glm::dot(g.axis, l.boxMin), g.cosSpread, g.sinSpread) <= 0.0f) continue;
    } else {
      const glm::vec3 dMin = l.boxMin - g.pMax, dMax = l.boxMin - g.pMin;
      const glm::vec2 d2 = lengths2(dMin, dMax);
      if (d2.x <= 0.0f ||
          lowestCosine(dMin, dMax, std::sqrt(d2.y), sphereCosines(g.axis, dMin, dMax).y) <= 0.0f)
        continue;
      t = float(linearisationBound(d2.x, l.invRange2, h2));
    }
    foldable.push_back({k, it.intensity * t});
  }
  thread_local std::vector<bool> folded;
  folded.assign(items.size(), false);
  if (rule.total) {
    std::sort(foldable.begin(), foldable.end());
    for (const Foldable& f : foldable) {
      const glm::vec3 b = result.check + f.t;
      if (maxOf(b) > kFoldMargin * rule.error * maxOf(sum - b)) break;
      result.check = b;
      folded[std::size_t(f.item)] = true;
    }
  } else {
    for (const Foldable& f : foldable) {
      const glm::vec3 b = items[std::size_t(f.item)].error + f.t;
      if (maxOf(b) > kMargin * rule.error * maxOf(sum)) continue;
      result.check = glm::max(result.check, b);
      folded[std::size_t(f.item)] = true;
    }
  }

  // The cut's entries: the far field first, then tree by tree (the bounds are set above).
  FarField far(centre);
  thread_local std::vector<std::uint32_t> byTree[3];
  for (auto& e : byTree) e.clear();
  for (const int k : settled) {
    const Item& it = items[std::size_t(k)];
    if (it.dark) continue;  // contributes nothing anywhere in the tile
    const Node& l = node(it.tree, leafOfSlot_[std::size_t(it.representative)]);
    if (folded[std::size_t(k)]) {
      if (it.tree == 0) {
        far.addDirectional(l.boxMin, it.intensity);
      } else {  // a spot folds only where its cone lets all light through: a point light there
        far.addPoint(l.boxMin, l.invRange2, it.intensity);
      }
      continue;
    }
    // The representative itself: direction or position, and 1/range²; a spot's cone; the
    // node's intensity.
    std::vector<std::uint32_t>& e = byTree[it.tree];
    for (const float w : {l.boxMin.x, l.boxMin.y, l.boxMin.z, it.tree == 0 ? 0.0f : l.invRange2})
      e.push_back(floatToBits(w));
    float coneOffset = 0.0f;
    if (it.tree == 2) {
      const SpotCone& cone = spotCone(it.representative);
      for (const float w : {cone.axis.x, cone.axis.y, cone.axis.z, cone.scale})
        e.push_back(floatToBits(w));
      coneOffset = cone.offset;
    }
    for (const float w : {it.intensity.x, it.intensity.y, it.intensity.z, coneOffset})
      e.push_back(floatToBits(w));
  }
  result.folded = far.count();
  if (!far.empty()) far.write(entries);
  for (int t = 0; t < 3; ++t) {
    result.counts[t] = int(byTree[t].size() / (t == 2 ? 12 : 8));
    entries.insert(entries.end(), byTree[t].begin(), byTree[t].end());
  }
  return result;
}

}  // namespace manylight
