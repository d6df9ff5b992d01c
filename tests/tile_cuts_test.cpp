// Tile cuts (cuts/tile_cuts.h) without GL: every shared cut, its far field included
// (cuts/far_field.h), evaluated in double precision at every pixel of its square, is
// within the bounds the pixels check against.
#include "cuts/tile_cuts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "bake/light_pack.h"
#include "bake/light_tree.h"
#include "bake/light_tree_layout.h"
#include "bake/light_tree_pack.h"
#include "cuts/cut_heap.h"
#include "cuts/far_field.h"
#include "generators/light_layouts.h"
#include "scene/shading_model.h"
#include "tests/far_field_support.h"
#include "tests/tile_cuts_support.h"

namespace manylight {
namespace {

using layout::floatOf;

// How many of the shared cuts are full (RegionCut::full, kFullCutBit).
int fullCuts(const TileCuts& cuts) {
  int full = 0;
  for (int c = 0; c < cuts.sharedCuts; ++c)
    full += (cuts.texels.head[8 * c + 7] & kFullCutBit) != 0;
  return full;
}

// The total rule's shared cuts of `lights` over `g`, on two threads.
TileCuts totalRuleCuts(const SyntheticGBuffer& g, const std::vector<Light>& lights, float epsilon,
                       int tileSize, int maxCut) {
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  return cutter.cut(g.pixels(), tileSize, CutRule{epsilon, true, maxCut}, 2);
}

Checked checkTotalRule(const std::vector<Light>& lights, float epsilon, int tileSize,
                       int maxCut = 8000) {
  const SyntheticGBuffer g;
  return checkCuts(g, lights, totalRuleCuts(g, lights, epsilon, tileSize, maxCut));
}

TEST(TileCuts, SharedCutsStayWithinTheirBoundsAtEveryPixel) {
  const struct {
    const char* name;
    LightLayout layout;
    int count;
  } cases[] = {{"uniform", LightLayout::Uniform, 2000},
               {"mixed", LightLayout::Mixed, 1500},
               {"clustered", LightLayout::Clustered, 2000},
               {"street", LightLayout::Street, 2000},  // spots whose cones' edges cross it
               {"two", LightLayout::Mixed, 2}};
  for (const auto& k : cases) {
    for (const int tile : {4, 16}) {
      const Checked c = checkTotalRule(layoutLights(k.layout, k.count, 7), 0.02f, tile);
      SCOPED_TRACE(std::string(k.name) + " tile " + std::to_string(tile));
      EXPECT_GT(c.sharedPixels, kSize * kSize / 2);  // most pixels share a cut
      // Most shared cuts fold entries into a far field, whose error the check above covers
      // (spots whose cones' edges cross the group do not fold).
      if (k.count > 2 && k.layout != LightLayout::Street) {
        EXPECT_GT(c.farFieldPixels, c.sharedPixels / 2);
      }
      EXPECT_EQ(c.failing, 0);
      // The ceiling patch's squares split by surface: every covered pixel shares a cut, and
      // no cut is shared by normals over 90° apart.
      EXPECT_EQ(c.perPixel, 0);
      EXPECT_EQ(c.mixedSurfaces, 0);
      // The bound itself, with 1e-4 for its single-precision sums against the double ones.
      EXPECT_LE(c.worstOverBound, 1.0001);
    }
  }
}

// Spots over the floor whose axes fan out by at most 2e-3 rad (a spread below float's
// resolution of a cosine near 1), half with hard edges (inner = outer angle), their cones'
// edges across the floor and the wall: the spot nodes' cone bounds (cuts/lane_cones.h) hold
// at every pixel under the total rule, where a bound a hair too tight at a hard edge would
// leave a lit node out as dark.
TEST(TileCuts, SpotConeBoundsHoldAtHardEdgesOfFannedCones) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Light> lights(2000);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Light& l = lights[i];
    l.type = LightType::Spot;
    l.position = {-3.0f + 9.0f * float(i) / 2000.0f, 4.0f + 0.01f * u(rng), 0.01f * u(rng)};
    l.direction = glm::normalize(glm::vec3(2e-3f * u(rng), -1.0f, 2e-3f * u(rng)));
    l.outerConeAngle = 0.9f;
    l.innerConeAngle = i % 2 == 0 ? 0.9f : 0.5f;
    l.colour = {1.0f, 0.75f, 0.45f};
    l.intensity = 120.0f / 2000.0f;
  }
  for (const int tile : {4, 16}) {
    const Checked c = checkTotalRule(lights, 0.02f, tile);
    EXPECT_GT(c.sharedPixels, kSize * kSize / 2) << "tile " << tile;
    EXPECT_EQ(c.failing, 0) << "tile " << tile;
    EXPECT_LE(c.worstOverBound, 1.0001) << "tile " << tile;
  }
}

// The words of pixel i's shared cut in `c`: its header but the entries' offset, then its
// entries (up to the next cut's, as TileCutter::cut lays them out in order); none if it has
// no shared cut.
std::vector<std::uint32_t> cutWords(const TileCuts& c, const std::vector<std::uint32_t>& texels,
                                    std::size_t i) {
  const std::uint32_t cut = c.cutOfPixel[i];
  if (cut == kNoSharedCut) return {};
  const std::uint32_t* header = texels.data() + 8 * std::size_t(cut);
  const std::size_t first = header[0];
  const std::size_t end = int(cut) + 1 < c.sharedCuts ? std::size_t(header[8]) : texels.size() / 4;
  std::vector<std::uint32_t> words(header + 1, header + 8);
  words.insert(words.end(), texels.begin() + std::ptrdiff_t(4 * first),
               texels.begin() + std::ptrdiff_t(4 * end));
  return words;
}

// Nodes are decoded as cuts first reach them, by whichever thread gets there first: a
// fresh cutter cutting on four threads finds, pixel by pixel, the very cuts a fresh one
// finds on one (which thread takes which square, and so the cuts' order, may differ).
TEST(TileCuts, NodesDecodedOnFirstUseGiveTheSameCutsOnAnyNumberOfThreads) {
  const SyntheticGBuffer g;
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 3000, 11);
  const PackedTrees packed = packLightTrees(buildLightTrees(lights));
  const CutRule rule{0.02f, false, 1000};
  const TileCuts one = TileCutter(packed, lights).cut(g.pixels(), 4, rule, 1);
  const TileCuts four = TileCutter(packed, lights).cut(g.pixels(), 4, rule, 4);
  EXPECT_GT(one.sharedCuts, 0);
  EXPECT_EQ(one.sharedCuts, four.sharedCuts);
  EXPECT_EQ(one.boundEvaluations(), four.boundEvaluations());
  const std::vector<std::uint32_t> oneTexels = one.texels.flat(), fourTexels = four.texels.flat();
  for (std::size_t i = 0; i < one.cutOfPixel.size(); ++i)
    ASSERT_EQ(cutWords(one, oneTexels, i), cutWords(four, fourTexels, i)) << "pixel " << i;
}

// TileCuts::work counts every cut the CPU finds by its kind (cuts/tile_cuts.h), the same on
// any number of threads. 64×64 pixels in 16×16 tiles: four 32×32
// squares (or their surfaces) find seeds. With at most 400 nodes at ε = 0.001 groups fill
// up, start over from the roots and fill up again; under the total rule, full seeds leave
// their quarters to start from the roots, and full cuts far off the rule have their pixels
// probed.
TEST(TileCuts, CutWorkCountsEveryCutByKind) {
  const SyntheticGBuffer g;
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 2000, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const auto kind = [](const TileCuts& c, CutKind k) { return c.work[std::size_t(k)]; };
  for (const CutRule& rule :
       {CutRule{0.02f, false, 2000}, CutRule{0.001f, false, 400}, CutRule{0.02f, true, 400}}) {
    const TileCuts one = cutter.cut(g.pixels(), 16, rule, 1);
    const TileCuts four = cutter.cut(g.pixels(), 16, rule, 4);
    for (int k = 0; k < kCutKinds; ++k) {
      const CutWork& a = one.work[std::size_t(k)];
      const CutWork& b = four.work[std::size_t(k)];
      EXPECT_EQ(a.cuts, b.cuts) << k;
      EXPECT_EQ(a.full, b.full) << k;
      EXPECT_EQ(a.bounds, b.bounds) << k;
      EXPECT_LE(a.full, a.cuts) << k;
      EXPECT_EQ(a.cuts == 0, a.bounds == 0) << k;
    }
    EXPECT_GE(kind(one, CutKind::Seed).cuts, 4);  // more where a square splits by its normals
    if (!rule.total) {
      EXPECT_GT(kind(one, CutKind::FromSeed).cuts, 0);
    }
    EXPECT_EQ(kind(one, CutKind::Cell).cuts, 0);
    if (rule.error < 0.01f) {
      EXPECT_GT(kind(one, CutKind::Retry).full, 0);
      EXPECT_GT(kind(one, CutKind::FromRoots).cuts, 0);
    }
    EXPECT_EQ(kind(one, CutKind::Probe).cuts > 0, rule.total);
  }
}

// Each thread's entries go into chunks (CutRule::chunkWords), laid out one after another:
// with chunks of 64 words, closed after nearly every square, the frame's texels are word for
// word those of one chunk, and on two threads each pixel's cut is the same.
TEST(TileCuts, EntriesInManyChunksLayOutAsInOne) {
  const SyntheticGBuffer g;
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 3000, 11);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CutRule rule{0.02f, false, 1000};
  const TileCuts one = cutter.cut(g.pixels(), 4, rule, 1);
  const TileCuts oneTwo = cutter.cut(g.pixels(), 4, rule, 2);
  rule.chunkWords = 64;
  const TileCuts many = cutter.cut(g.pixels(), 4, rule, 1);
  const TileCuts manyTwo = cutter.cut(g.pixels(), 4, rule, 2);
  EXPECT_GT(one.texels.words(), 100 * rule.chunkWords);
  EXPECT_EQ(many.texels.flat(), one.texels.flat());
  EXPECT_EQ(many.cutOfPixel, one.cutOfPixel);
  const std::vector<std::uint32_t> a = oneTwo.texels.flat(), b = manyTwo.texels.flat();
  for (std::size_t i = 0; i < one.cutOfPixel.size(); ++i)
    ASSERT_EQ(cutWords(oneTwo, a, i), cutWords(manyTwo, b, i)) << "pixel " << i;
}

// A 4×4 square (the finest) whose cut fills up before the rule holds with the CPU's margin,
// but holds without it, is still shared: its pixels check the rule for themselves. With
// 2,000 uniform lights, the total rule and at most 1,600 nodes, 538 of the 3,712 covered
// pixels shared a cut before, and every pixel stays within its cut's bound.
TEST(TileCuts, AFullCutAtTheFinestSizeIsSharedWhenItMeetsTheRuleWithoutTheMargin) {
  const Checked c = checkTotalRule(layoutLights(LightLayout::Uniform, 2000, 7), 0.02f, 4, 1600);
  EXPECT_GT(c.sharedPixels, 1000);
  EXPECT_EQ(c.sharedPixels + c.perPixel, 3712);
  EXPECT_EQ(c.failing, 0);
  EXPECT_LE(c.worstOverBound, 1.0001);
}

// Under the total rule, a full cut that smaller groups would not bring within the rule (at
// the finest size, or kSplitShortfall from its target) is shared and marked full where
// every node's bound is within a quarter of ε of the estimate and no probed pixel's own cut
// comes close to the rule: its pixels take it instead of walking cuts of their own, which would
// reach their maximum too. Its bound still holds at every pixel. Under the node rule full cuts are
// not shared. (2,000 uniform lights, at most 400 nodes: 158 full cuts, 2,698 of 3,712 pixels
// on them; before, every pixel walked its own cut.)
TEST(TileCuts, UnderTheTotalRuleAHopelessCutIsSharedAndMarkedFull) {
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 2000, 7);
  const SyntheticGBuffer g;
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const TileCuts total = cutter.cut(g.pixels(), 16, CutRule{0.02f, true, 400}, 2);
  const Checked c = checkCuts(g, lights, total);
  EXPECT_GT(c.sharedPixels, 2 * c.perPixel);
  EXPECT_EQ(c.sharedPixels + c.perPixel, 3712);
  EXPECT_EQ(c.failing, 0);
  EXPECT_LE(c.worstOverBound, 1.0001);
  EXPECT_GT(fullCuts(total), total.sharedCuts / 2);
  const TileCuts node = cutter.cut(g.pixels(), 16, CutRule{0.001f, false, 400}, 2);
  EXPECT_GT(checkCuts(g, lights, node).perPixel, 0);
  EXPECT_EQ(fullCuts(node), 0);
}

// Under the total rule, a square of seeds (twice the tile) whose cut is as hopeless as a full
// cut to share shares it with all its pixels, instead of each quarter finding a full cut of
// its own from the roots. Its bound holds at every pixel. (8,192 uniform lights, at most 2,000
// nodes: 15 cuts, all full, one of them shared by a whole 32×32 square; before, each held
// at most a 16×16 square.)
TEST(TileCuts, AHopelessSquareOfSeedsSharesItsFullCut) {
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 8192, 7);
  const SyntheticGBuffer g;
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const TileCuts cuts = cutter.cut(g.pixels(), 16, CutRule{0.02f, true, 2000}, 2);
  std::map<std::uint32_t, int> pixelsOfCut;
  for (const std::uint32_t cut : cuts.cutOfPixel) {
    if (cut != kNoSharedCut) ++pixelsOfCut[cut];
  }
  int largest = 0;
  for (const auto& [cut, pixels] : pixelsOfCut) largest = std::max(largest, pixels);
  EXPECT_EQ(largest, 32 * 32);
  const Checked c = checkCuts(g, lights, cuts);
  EXPECT_EQ(c.sharedPixels, 3712);
  EXPECT_EQ(c.failing, 0);
  EXPECT_LE(c.worstOverBound, 1.0001);
}

// Past rule.texelsPerPixel, a square's (32×32 here) costliest cuts per pixel are dropped and
// their pixels walk; the cuts kept are the ones found without the budget, renumbered.
TEST(TileCuts, EachSquaresCutsStayWithinTheirTexelBudget) {
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 2000, 7);
  const SyntheticGBuffer g;
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CutRule rule{0.02f, true, 400};
  const TileCuts free = cutter.cut(g.pixels(), 16, rule, 2);
  rule.texelsPerPixel = 20;
  const TileCuts held = cutter.cut(g.pixels(), 16, rule, 2);
  const std::vector<std::uint32_t> freeTexels = free.texels.flat(), heldTexels = held.texels.flat();
  auto words = [&](const TileCuts& t, std::uint32_t c) {  // cut c's header and entries
    const std::vector<std::uint32_t>& all = &t == &free ? freeTexels : heldTexels;
    const std::size_t end = c + 1 < std::uint32_t(t.sharedCuts) ? all[8 * (c + 1)] : all.size() / 4;
    std::vector<std::uint32_t> w(all.begin() + 8 * c + 1, all.begin() + 8 * c + 8);
    w.insert(w.end(), all.begin() + 4 * all[8 * c], all.begin() + 4 * end);
    return w;
  };
  std::map<int, std::size_t> used, budget;  // entry texels by square (x / 32 + 2 · y / 32)
  std::set<std::uint32_t> counted;
  for (std::size_t i = 0; i < held.cutOfPixel.size(); ++i) {
    const int square = int(i % kSize) / 32 + 2 * (int(i / kSize) / 32);
    if (g.normal[i * 4 + 3] == 0.0f) continue;  // background
    budget[square] += rule.texelsPerPixel;
    if (free.cutOfPixel[i] == kNoSharedCut) continue;
    const std::uint32_t c = held.cutOfPixel[i];
    if (c == kNoSharedCut) continue;
    EXPECT_EQ(words(held, c), words(free, free.cutOfPixel[i])) << "pixel " << i;
    if (counted.insert(c).second) used[square] += words(held, c).size() / 4 - 1;
  }
  ASSERT_LT(held.sharedCuts, free.sharedCuts);
  EXPECT_GT(held.sharedCuts, 0);
  for (const auto& [square, texels] : used) EXPECT_LE(texels, budget[square]) << square;
  const Checked c = checkCuts(g, lights, held);
  EXPECT_EQ(c.failing, 0);
  EXPECT_GT(c.perPixel, checkCuts(g, lights, free).perPixel);
}

// Groups larger than the finest split once their cut would exceed kSplitCut entries at
// ε = kSplitError, proportionally more at smaller ε, never past the maximum; groups one level
// above the finest (CutRule::splitScale, kNearFinestSplit) at twice that.
TEST(TileCuts, GroupsSplitAtLargerCutsForSmallerErrors) {
  EXPECT_EQ(splitCut(CutRule{0.02f, false, 2000}), 1000);
  EXPECT_EQ(splitCut(CutRule{0.05f, false, 2000}), 1000);
  EXPECT_EQ(splitCut(CutRule{0.01f, false, 2000}), 2000);
  EXPECT_EQ(splitCut(CutRule{0.01f, false, 4000}), 2000);
  EXPECT_EQ(splitCut(CutRule{0.005f, false, 4000}), 4000);
  EXPECT_EQ(splitCut(CutRule{0.005f, false, 1500}), 1500);
  CutRule nearFinest{0.02f, false, 8000};
  nearFinest.splitScale = kNearFinestSplit;
  EXPECT_EQ(splitCut(nearFinest), 2000);
  nearFinest.error = 0.005f;
  EXPECT_EQ(splitCut(nearFinest), 8000);
  nearFinest.maxCut = 3000;
  EXPECT_EQ(splitCut(nearFinest), 3000);
}

// The covered pixels of the square of `size` at (x0, y0).
std::vector<int> squareOf(const SyntheticGBuffer& g, int x0, int y0, int size) {
  std::vector<int> pixels;
  for (int y = y0; y < y0 + size; ++y) {
    for (int x = x0; x < x0 + size; ++x) {
      if (g.normal[(std::size_t(y) * kSize + x) * 4 + 3] != 0.0f) pixels.push_back(y * kSize + x);
    }
  }
  return pixels;
}

// One group's cut as a frame's only shared cut.
TileCuts asTileCuts(const RegionCut& r, const std::vector<std::uint32_t>& entries,
                    const std::vector<int>& pixels) {
  TileCuts t;
  t.cutOfPixel.assign(std::size_t(kSize * kSize), kNoSharedCut);
  for (const int i : pixels) t.cutOfPixel[std::size_t(i)] = 0;
  t.sharedCuts = 1;
  t.texels.head.assign(8, 0u);
  r.writeHeader(2, t.texels.head.data());
  t.texels.head.insert(t.texels.head.end(), entries.begin(), entries.end());
  return t;
}

// A 16×16 square's cut started from the cut of the 32×32 square that holds it (CutSeed)
// costs a fraction of the bounds of one from the roots, and stays within its bounds at
// every pixel. A full cut still makes a seed: the cut found so far.
TEST(TileCuts, ACutStartedFromItsSquaresSeedHoldsForLess) {
  const SyntheticGBuffer g;
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 1500, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const std::vector<int> small = squareOf(g, 0, 0, 16);
  ShadingRegion outer, inner;
  ASSERT_TRUE(shadingRegion(g.pixels(), squareOf(g, 0, 0, 32), outer));
  ASSERT_TRUE(shadingRegion(g.pixels(), small, inner));
  const CutRule rule{0.02f, true, 8000};
  CutSeed seed;
  std::vector<std::uint32_t> unused, fresh, seeded;
  EXPECT_FALSE(cutter.cutRegion(outer, rule, false, unused, nullptr, &seed).perPixel);
  EXPECT_TRUE(unused.empty());
  EXPECT_GT(seed.far.count(), 0);
  const RegionCut fromRoots = cutter.cutRegion(inner, rule, false, fresh);
  const RegionCut fromSeed = cutter.cutRegion(inner, rule, false, seeded, &seed);
  ASSERT_FALSE(fromSeed.perPixel);
  EXPECT_LT(2 * fromSeed.bounds, fromRoots.bounds);
  const Checked c = checkCuts(g, lights, asTileCuts(fromSeed, seeded, small));
  EXPECT_EQ(c.sharedPixels, 256);
  EXPECT_EQ(c.failing, 0);
  EXPECT_LE(c.worstOverBound, 1.0001);

  CutSeed fullSeed;
  EXPECT_TRUE(cutter.cutRegion(outer, CutRule{0.02f, true, 40}, false, unused, nullptr, &fullSeed)
                  .perPixel);
  std::vector<std::uint32_t> fromFull;
  const RegionCut fromFullSeed = cutter.cutRegion(inner, rule, false, fromFull, &fullSeed);
  ASSERT_FALSE(fromFullSeed.perPixel);
  EXPECT_LT(fromFullSeed.bounds, fromRoots.bounds);
  const Checked d = checkCuts(g, lights, asTileCuts(fromFullSeed, fromFull, small));
  EXPECT_EQ(d.sharedPixels, 256);
  EXPECT_EQ(d.failing, 0);
  EXPECT_LE(d.worstOverBound, 1.0001);
}

// The cut's heap keeps std::push_heap's and std::pop_heap's layout, so cuts list their
// entries in the same order (and images stay bit for bit) whichever is used.
TEST(TileCuts, CutHeapLaysKeysOutAsTheStandardHeapDoes) {
  std::mt19937_64 random(7);
  std::vector<std::uint64_t> ours, standard;
  std::uint64_t next = 0;
  for (int step = 0; step < 20000; ++step) {
    if (ours.empty() || random() % 3 != 0) {
      const std::uint64_t key = (random() >> 32) << 32 | next++;  // unique, as the cut's are
      ours.push_back(key);
      standard.push_back(key);
      cut_heap::pushHeap(ours);
      std::push_heap(standard.begin(), standard.end());
    } else {
      cut_heap::popHeap(ours);
      std::pop_heap(standard.begin(), standard.end());
      ASSERT_EQ(ours.back(), standard.back());
      ours.pop_back();
      standard.pop_back();
    }
    ASSERT_EQ(ours, standard) << "step " << step;
  }
}

TEST(TileCuts, SpecularPixelsAreLeftToThemselves) {
  SyntheticGBuffer g;
  g.specular[0] = 0.5f;  // pixel (0, 0): its square cuts per pixel
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 100, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const GBufferPixels px{kSize, kSize, g.position.data(), g.normal.data(), g.specular.data()};
  const TileCuts cuts = cutter.cut(px, 16, CutRule{}, 1);
  EXPECT_EQ(cuts.cutOfPixel[0], kNoSharedCut);
  EXPECT_NE(cuts.cutOfPixel[1], kNoSharedCut);  // its neighbour shares a cut
}

}  // namespace
}  // namespace manylight
