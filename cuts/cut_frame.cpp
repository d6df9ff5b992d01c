// The frame's shared cuts (cuts/tile_cuts.h): squares of pixels, their seeds, the splits of
// groups whose cuts fill up, and the texels of all the cuts; TileCutter::cutRegion (in
// cut_region.cpp) finds each group's cut.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <memory>

#include "bake/light_tree_layout.h"
#include "cuts/threads.h"
#include "cuts/tile_cuts.h"

namespace manylight {

namespace {

// How near its target a probed pixel's own cut may end for the group's pixels to walk
// (ownCutsFit says why).
constexpr float kWalkShortfall = 16.0f;
// Where the group may have an exact cut instead (CutRule::exactFull), its pixels walk only
// where all five probed pixels meet the rule with cuts of at most 1 / kWalkCost of the lights
// (the probes stop at the first that does not): a pixel's walk costs about kWalkCost light
// evaluations per node of its cut (several passes, a node's bounds against a light's shading,
// loops that differ from pixel to pixel), and one that reaches the maximum sums every light
// after it where the shader's loop budget has room for them. Measured at 16,384 lights (320×240,
// total rule), frames with no walks and with walks wherever all five probes met the rule:
// on-surfaces (ε = 0.02) 1.49 and 1.59 s; clustered (ε = 0.005) 1.08 and 1.33 s; lights at one
// point (ε = 0.02) 1.03 and 0.20 s; the reference 0.8 s. At 640×480, clustered at ε = 0.02 walked
// cuts of 1,332 nodes on average where all five met the rule: 6.4 s of the shader's time, about 24
// light evaluations a node, against the reference's 3.2 s. With kWalkCost = 24 the three frames
// take 1.55, 1.08 and 0.19 s.
constexpr int kWalkCost = 24;

// One thread's cuts (numbered in order; cutOfPixel holds these numbers until the merge) and
// their entries.
struct Part {
  std::size_t chunkWords;  // CutRule::chunkWords
  std::vector<RegionCut> cuts;
  std::vector<std::size_t> entry;                  // each cut's first word in its chunk
  std::vector<std::uint32_t> entries;              // the chunk being filled
  std::vector<std::vector<std::uint32_t>> chunks;  // those filled
  std::vector<std::size_t> chunkEnd;               // per chunk filled, the cuts up to its end
  CutWorks work{};  // the cuts found by kind, and their node bounds (split groups' too)
  int perPixel = 0, splits = 0;

  explicit Part(std::size_t words) : chunkWords(words) { entries.reserve(chunkWords); }
  void closeFullChunk() {
    if (entries.size() < chunkWords) return;
    chunks.push_back(std::move(entries));
    chunkEnd.push_back(cuts.size());
    entries = {};
    entries.reserve(chunkWords);
  }
  void count(CutKind kind, const RegionCut& r) {
    work[std::size_t(kind)].add(r.bounds, r.perPixel || r.full);
  }
  std::size_t words() const {
    std::size_t n = entries.size();
    for (const auto& c : chunks) n += c.size();
    return n;
  }
};

// A group of a square's covered pixels (indices y · width + x), and the seed its cut
// starts from.
struct Group {
  int x0, y0, size;
  std::vector<int> pixels;
  std::shared_ptr<const CutSeed> seed;
};

// Splits `group` into its quarters, which start from `seed`.
void quarters(const GBufferPixels& px, const Group& group, std::vector<Group>& todo,
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
}

// Splits `group` into its two surfaces (cuts/pixel_groups.h), which start from its seed.
bool surfaces(const GBufferPixels& px, const Group& group, const ShadingRegion& g,
              std::vector<Group>& todo) {
  Group a{group.x0, group.y0, group.size, {}, group.seed}, b = a;
  if (!splitByNormal(px, group.pixels, g, a.pixels, b.pixels)) return false;
  todo.push_back(std::move(a));
  todo.push_back(std::move(b));
  return true;
}

// Whether pixel i's Phong lobe outweighs its Lambert term: a metal, say.
bool lobeDominated(const GBufferPixels& px, std::size_t i) {
  const float* ks = px.specular + 4 * i;
  const float* a = px.albedo + 4 * i;
  return std::max({ks[0], ks[1], ks[2]}) > std::max({a[0], a[1], a[2]});
}

// Splits `group` into its lobe-dominated pixels and the rest, which start from its seed.
// False when all are of one kind. A pixel checks the shared cut with its own albedo and
// specular colour, while the CPU weighs the cut's bounds by the group's means: a metal pixel
// beside Lambert ones would meet lobe bounds far looser than its own estimate (all lobe)
// allows, and walk its own cut. Seeds stay mixed: a quarter starts from a cut refined for
// both kinds, and so does each kind's group.
bool materials(const GBufferPixels& px, const Group& group, std::vector<Group>& todo) {
  Group a{group.x0, group.y0, group.size, {}, group.seed}, b = a;
  for (const int i : group.pixels) (lobeDominated(px, std::size_t(i)) ? a : b).pixels.push_back(i);
  if (a.pixels.empty() || b.pixels.empty()) return false;
  todo.push_back(std::move(a));
  todo.push_back(std::move(b));
  return true;
}

// Whether the pixels of `group`, whose cut under the total rule filled up (RegionCut::full),
// may find cuts of their own within rule.ownCut nodes: true when one of five of them does on
// the CPU, or comes within kWalkShortfall of its target. A point's bounds can be far tighter
// than a square's: with 65,536 clustered lights (320×240), most pixels of full squares met
// the rule in their own walks, where the CPU's cuts of the five mostly ended 4–8 times over
// its target at a quarter of ε (kTotalMargin); with 65,536 mixed lights the five ended with
// bounds above their estimates. Where pixels come that close, their walks' cuts were also the
// closer where they reached the maximum: taking the group's full cut there instead put the
// worst pixel of 16,384 clustered lights at ε = 0.005 (320×240) 3.5% off, against 0.35%.
// The probes bound nodes as the walks do (CutRule::walkBounds: no lower bound on a lobe), and
// the walks bound spot nodes' cone factors as the shared cuts do (glsl/lightcuts_walk.glsl's
// spotConeFactor): with the walks' cone factor at 1 and no lower bound, probes under 65,536
// street lights met the rule where the walks of 137,000 pixels reached the maximum.
bool ownCutsFit(const TileCutter& cutter, CutWorkspace& work, const GBufferPixels& px,
                const Group& group, const CutRule& rule, Part& part) {
  CutRule own = rule;
  own.maxCut = std::min(rule.ownCut, rule.maxCut);
  own.shareFull = false;
  own.walkBounds = true;
  std::vector<std::uint32_t> unused;
  const std::size_t n = group.pixels.size();
  for (const std::size_t k : {n / 2, std::size_t(0), n - 1, n / 4, 3 * n / 4}) {
    ShadingRegion point;
    if (!shadingRegion(px, {group.pixels[k]}, point)) continue;
    // One normal: no spread (shadingRegion allows round-off among a group's, which gives a
    // light behind the normal a bound of sin(spread), and a dark pixel a cut that fills up).
    point.cosSpread = 1.0f;
    point.sinSpread = 0.0f;
    const RegionCut r = cutter.cutRegion(work, point, own, true, unused);
    part.count(CutKind::Probe, r);
    if (rule.exactFull) {
      const int size = r.counts[0] + r.counts[1] + r.counts[2] + r.folded;
      if (r.perPixel || size * kWalkCost > cutter.lights()) return false;
    } else if (!r.perPixel || r.shortfall < kWalkShortfall) {
      return true;
    }
  }
  return rule.exactFull;
}

// Under the total rule, a cut that filled up far from its target (full, or too coarse to
// share: kSplitShortfall) leaves its pixels to their own cuts where those may meet the rule
// (ownCutsFit, asked once per group), rather than to quarters, which would fill up too.
struct OwnCuts {
  const TileCutter& cutter;
  CutWorkspace& work;
  const GBufferPixels& px;
  Group& group;
  const CutRule& rule;
  Part& part;
  int walks = -1;  // ownCutsFit's answer, once asked
  bool farOff(const RegionCut& r) const {
    return rule.total && (r.full || (r.perPixel && !(r.shortfall < kSplitShortfall)));
  }
  bool fit() {
    if (walks < 0) walks = ownCutsFit(cutter, work, px, group, rule, part) ? 1 : 0;
    return walks == 1;
  }
};

// The cut of `own.group`, of the shading points `g`, its entries appended to the part's.
// A cut from the group's seed that is too fine here starts over from the roots, as does one
// full from it (a seeded cut ends farther from its target, and the choices after go by how
// far), unless the group's pixels walk their own cuts either way.
RegionCut groupCut(OwnCuts& own, const ShadingRegion& g, bool finest) {
  Part& part = own.part;
  const std::size_t entry = part.entries.size();
  const CutSeed* seed = own.group.seed.get();
  RegionCut r = own.cutter.cutRegion(own.work, g, own.rule, finest, part.entries, seed);
  part.count(seed ? CutKind::FromSeed : CutKind::FromRoots, r);
  if ((r.perPixel || r.full) && seed && !(own.farOff(r) && own.fit())) {
    part.entries.resize(entry);
    own.group.seed = nullptr;
    r = own.cutter.cutRegion(own.work, g, own.rule, finest, part.entries);
    part.count(CutKind::Retry, r);
  }
  return r;
}

// The covered pixels of the square of `top` pixels at (x0, y0) that share cuts (and are
// marked in `only`, when given).
Group squareAt(const GBufferPixels& px, int x0, int y0, int top,
               const std::vector<std::uint8_t>* only) {
  Group first{x0, y0, top, {}, nullptr};
  for (int y = y0; y < std::min(y0 + top, px.height); ++y) {
    for (int x = x0; x < std::min(x0 + top, px.width); ++x) {
      const std::size_t i = std::size_t(y) * px.width + x;
      if ((!only || (*only)[i]) && sharesCuts(px, i)) first.pixels.push_back(int(i));
    }
  }
  return first;
}

}  // namespace

std::size_t RegionCut::entryTexels() const {
  return std::size_t(2 * (counts[0] + counts[1]) + 3 * counts[2] +
                     (folded > 0 ? kFarFieldTexels : 0) + (lobes ? 2 : 0));
}

void RegionCut::writeHeader(std::uint32_t firstEntryTexel, std::uint32_t* words) const {
  assert(folded < (1 << 15) && zeros < (1 << 15));  // their bits (TileCuts)
  const std::uint32_t header[8] = {firstEntryTexel,
                                   std::uint32_t(counts[0]),
                                   std::uint32_t(counts[1]),
                                   std::uint32_t(counts[2]),
                                   layout::wordOf(check.x),
                                   layout::wordOf(check.y),
                                   layout::wordOf(check.z),
                                   std::uint32_t(folded) | (lobes ? kLobesBit : 0u) |
                                       std::uint32_t(zeros) << 16 | (full ? kFullCutBit : 0u)};
  std::copy_n(header, 8, words);
}

void RegionCut::writeTexels(std::size_t cut, const std::uint32_t* words, std::size_t count,
                            std::size_t& next, std::uint32_t* texels) const {
  writeHeader(std::uint32_t(next), texels + 8 * cut);
  std::copy_n(words, count * 4, texels + next * 4);
  next += count;
}

// Holds the cuts of one square (the part's from `firstCut` on; `pixels` the square's) to
// `budget` entry texels: while over it, drops the cut that costs the most texels per pixel
// it serves, full cuts first (not exact ones: they take none), whose pixels then walk cuts
// of their own.
static void holdToBudget(Part& part, std::size_t firstCut, const std::vector<int>& pixels,
                         std::size_t budget, std::vector<std::uint32_t>& cutOfPixel) {
  const std::size_t n = part.cuts.size() - firstCut;
  std::vector<std::size_t> texels(n), served(n, 0);
  std::size_t total = 0;
  for (std::size_t k = 0; k < n; ++k) total += texels[k] = part.cuts[firstCut + k].entryTexels();
  if (total <= budget) return;
  for (const int i : pixels) {
    const std::uint32_t c = cutOfPixel[std::size_t(i)];
    if (c != kNoSharedCut && c >= firstCut) ++served[c - firstCut];
  }
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = k;
  auto costlier = [&](std::size_t a, std::size_t b) {  // texels per pixel, compared exactly
    const RegionCut &ra = part.cuts[firstCut + a], &rb = part.cuts[firstCut + b];
    const bool fa = ra.full && !ra.exact, fb = rb.full && !rb.exact;  // exact: no texels
    if (fa != fb) return fa;
    const std::size_t x = texels[a] * served[b], y = texels[b] * served[a];
    return x != y ? x > y : a < b;
  };
  std::sort(order.begin(), order.end(), costlier);
  std::vector<std::uint32_t> number(n);  // each cut's new number, kNoSharedCut when dropped
  for (std::size_t j = 0; j < n && total > budget; ++j) {
    total -= texels[order[j]];
    number[order[j]] = kNoSharedCut;
    ++part.perPixel;
  }
  std::size_t kept = firstCut, next = n > 0 ? part.entry[firstCut] : part.entries.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (number[k] == kNoSharedCut) continue;
    const std::size_t from = part.entry[firstCut + k];
    if (from != next)
      std::copy(part.entries.begin() + std::ptrdiff_t(from),
                part.entries.begin() + std::ptrdiff_t(from + 4 * texels[k]),
                part.entries.begin() + std::ptrdiff_t(next));
    part.cuts[kept] = part.cuts[firstCut + k];
    part.entry[kept] = next;
    number[k] = std::uint32_t(kept++);
    next += 4 * texels[k];
  }
  part.cuts.resize(kept);
  part.entry.resize(kept);
  part.entries.resize(next);
  for (const int i : pixels) {
    std::uint32_t& c = cutOfPixel[std::size_t(i)];
    if (c != kNoSharedCut && c >= firstCut) c = number[c - firstCut];
  }
}

// Gives `pixels` an exact cut (RegionCut::exact) in place of `full`, a cut that filled up.
static void shareExact(Part& part, const std::vector<int>& pixels, const RegionCut& full,
                       std::vector<std::uint32_t>& cutOfPixel) {
  RegionCut exact;
  exact.full = exact.exact = true;
  exact.bounds = full.bounds;
  exact.shortfall = full.shortfall;
  for (const int i : pixels) cutOfPixel[std::size_t(i)] = std::uint32_t(part.cuts.size());
  part.cuts.push_back(exact);
  part.entry.push_back(part.entries.size());
}

// Gives `pixels` the cut `r`, its entries from `entry` on.
static void shareCut(Part& part, const std::vector<int>& pixels, const RegionCut& r,
                     std::size_t entry, std::vector<std::uint32_t>& cutOfPixel) {
  for (const int i : pixels) cutOfPixel[std::size_t(i)] = std::uint32_t(part.cuts.size());
  part.cuts.push_back(r);
  part.entry.push_back(entry);
}

// A square larger than the tile, `group` of shading points `g`: finds the cut its quarters
// start from and splits it into them, or gives its pixels a cut at once where its quarters'
// would fill up too.
static void seedSquare(const TileCutter& cutter, CutWorkspace& work, const GBufferPixels& px,
                       Group& group, const ShadingRegion& g, const CutRule& rule, Part& part,
                       std::vector<Group>& todo, std::vector<std::uint32_t>& cutOfPixel) {
  auto next = std::make_shared<CutSeed>();
  const std::size_t entry = part.entries.size();
  const RegionCut r =
      cutter.cutRegion(work, g, rule, false, part.entries, group.seed.get(), next.get());
  part.count(CutKind::Seed, r);
  OwnCuts own{cutter, work, px, group, rule, part};
  // Hopeless from the top (quarters would fill up too): an exact cut at once where it may be,
  // else its full cut, unless its pixels' own cuts may meet the rule.
  if ((r.exact || r.full) && !group.seed && !own.fit()) {
    if (r.exact) shareExact(part, group.pixels, r, cutOfPixel);
    if (r.full) {  // shared as a group's full cut is (not left to its pixels' own cuts)
      RegionCut shared = r;
      shared.perPixel = false;
      shareCut(part, group.pixels, shared, entry, cutOfPixel);
    }
    return;
  }
  part.entries.resize(entry);
  // A full cut is a start too: a quarter whose cut then fills up starts over below. Not under
  // the total rule, whose quarters then fill up as well: they start from the roots at once.
  quarters(px, group, todo, r.perPixel && rule.total ? nullptr : next);
}

// Cuts `square` and the groups it splits into, on one thread: the shared cuts go to `part`,
// each pixel's cut number (within the part) to `cutOfPixel`.
static void cutSquare(const TileCutter& cutter, CutWorkspace& work, const GBufferPixels& px,
                      Group square, int tileSize, const CutRule& rule, Part& part,
                      std::vector<std::uint32_t>& cutOfPixel) {
  const int fine = std::min(kFinestTile, tileSize);
  CutRule wider = rule;  // for groups whose quarters are of the finest size, or lobe-dominated
  wider.splitScale = kNearFinestSplit;
  std::vector<Group> todo;
  const std::size_t firstCut = part.cuts.size();
  const std::vector<int> pixels = square.pixels;
  if (!square.pixels.empty()) todo.push_back(std::move(square));
  while (!todo.empty()) {
    Group group = std::move(todo.back());
    todo.pop_back();
    if (group.size <= tileSize && px.albedo && materials(px, group, todo)) continue;
    ShadingRegion g;
    const bool cone = shadingRegion(px, group.pixels, g);
    // Normals over 90° apart leave no cosine bound: split without trying.
    const bool tried = cone && g.cosSpread >= 0.0f;
    if (group.size > tileSize) {  // a seed for the quarters
      if (tried) {
        seedSquare(cutter, work, px, group, g, rule, part, todo, cutOfPixel);
      } else if (!surfaces(px, group, g, todo)) {
        quarters(px, group, todo, group.seed);
      }
      continue;
    }
    RegionCut result;
    const std::size_t entry = part.entries.size();
    const bool finest = group.size <= fine;
    // Past materials(), a group's pixels are all lobe-dominated or none: its first speaks for it.
    const bool wide =
        !finest && (group.size <= 2 * fine ||
                    (px.albedo && px.specular && lobeDominated(px, std::size_t(group.pixels[0]))));
    OwnCuts own{cutter, work, px, group, wide ? wider : rule, part};
    if (tried) result = groupCut(own, g, finest);
    if (tried && own.farOff(result)) {  // split into its surfaces first, as any group alone
      const bool split = g.cosSpread < kSurfaceSpread && surfaces(px, group, g, todo);
      if (split || own.fit()) {
        part.entries.resize(entry);  // else its pixels walk cuts of their own
        ++(split ? part.splits : part.perPixel);
        continue;
      }
      if (rule.exactFull) {  // quarters would fill up too: its pixels sum every light
        part.entries.resize(entry);
        shareExact(part, group.pixels, result, cutOfPixel);
        continue;
      }
    }
    if (tried && !result.perPixel) {
      shareCut(part, group.pixels, result, entry, cutOfPixel);
      continue;
    }
    part.entries.resize(entry);
    if ((!cone || g.cosSpread < kSurfaceSpread) && surfaces(px, group, g, todo)) {
      ++part.splits;
      continue;
    }
    // Smaller squares have tighter bounds: try the quarters. Under the node rule the culprit
    // is mostly a light near one corner, which a quarter leaves out; under the total rule
    // the quarters may meet the rule, or take a full cut closer to it (RegionCut::full).
    if (cone && group.size > fine) {
      quarters(px, group, todo, group.seed);
      continue;
    }
    if (rule.exactFull && !own.fit()) {  // walks would cost more than summing every light
      shareExact(part, group.pixels, result, cutOfPixel);
      continue;
    }
    ++part.perPixel;
  }
  holdToBudget(part, firstCut, pixels, rule.texelsPerPixel * pixels.size(), cutOfPixel);
}

TileCuts TileCutter::cut(const GBufferPixels& px, int tileSize, const CutRule& rule, int threads,
                         const std::vector<std::uint8_t>* only) const {
  TileCuts out;
  out.cutOfPixel.assign(std::size_t(px.width) * px.height, kNoSharedCut);
  // Squares of `top` pixels find seed cuts for their quarters, down to squares of tileSize.
  const int top = tileSize << kSeedLevels;
  const int coarseX = (px.width + top - 1) / top;
  const int coarse = coarseX * ((px.height + top - 1) / top);
  threads = std::clamp(threads, 1, std::max(coarse, 1));
  std::vector<Part> parts;
  for (int t = 0; t < threads; ++t) parts.emplace_back(rule.chunkWords);
  // Each thread takes the next square not yet taken: their costs differ tenfold, so squares
  // dealt out in turn would leave one thread behind the others. partOf[t] says whose square
  // t was; the merge below renumbers each pixel's cut by it.
  std::atomic<int> nextSquare{0};
  std::vector<int> partOf(std::size_t(coarse), 0);
  auto work = [&](int index) {
    CutWorkspace workspace;
    for (int t; (t = nextSquare.fetch_add(1, std::memory_order_relaxed)) < coarse;) {
      partOf[std::size_t(t)] = index;
      cutSquare(*this, workspace, px,
                squareAt(px, (t % coarseX) * top, (t / coarseX) * top, top, only), tileSize, rule,
                parts[std::size_t(index)], out.cutOfPixel);
      parts[std::size_t(index)].closeFullChunk();
    }
  };
  onThreads(threads, work);

  // Number the cuts part after part, and lay out headers, then entries, part after part and
  // chunk after chunk.
  std::vector<std::uint32_t> firstCut(parts.size(), 0);
  std::size_t cuts = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    firstCut[k] = std::uint32_t(cuts);
    cuts += parts[k].cuts.size();
    addWorks(out.work, parts[k].work);
    out.perPixelGroups += parts[k].perPixel;
    out.surfaceSplits += parts[k].splits;
  }
  out.sharedCuts = int(cuts);
  out.made = out.sharedCuts + out.perPixelGroups;
  for (std::size_t i = 0; i < out.cutOfPixel.size(); ++i) {
    std::uint32_t& c = out.cutOfPixel[i];
    if (c == kNoSharedCut) continue;
    const int x = int(i % std::size_t(px.width)), y = int(i / std::size_t(px.width));
    c += firstCut[std::size_t(partOf[std::size_t((y / top) * coarseX + x / top)])];
  }
  out.texels.head.assign(8 * cuts, 0u);
  std::size_t next = 2 * cuts, cut = 0;  // the texel where a part's entries start
  for (Part& part : parts) {
    std::size_t chunkStart = next, c = 0;
    for (std::size_t k = 0; k < part.cuts.size(); ++k, ++cut) {
      for (; c < part.chunkEnd.size() && k >= part.chunkEnd[c]; ++c)
        chunkStart += part.chunks[c].size() / 4;
      const RegionCut& r = part.cuts[k];
      out.exactCuts += r.exact ? 1 : 0;
      r.writeHeader(std::uint32_t(chunkStart + part.entry[k] / 4),
                    out.texels.head.data() + 8 * cut);
    }
    next += part.words() / 4;
    for (auto& chunk : part.chunks) out.texels.append(std::move(chunk));
    out.texels.append(std::move(part.entries));
  }
  return out;
}

}  // namespace manylight
