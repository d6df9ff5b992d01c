// Cell cuts (cuts/cell_cuts.h) without GL: cuts kept per cell of space from frame to frame
// hold for every pixel as the view moves, are dropped past their limit, and fall back to
// squares where cells fill up.
#include "cuts/cell_cuts.h"

#include <gtest/gtest.h>

#include <iostream>

#include "bake/light_pack.h"
#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "generators/light_layouts.h"
#include "tests/tile_cuts_support.h"

namespace manylight {
namespace {

// Whether `g` holds the shading point of pixel i of `gb` (as CellCuts decides it).
bool regionHolds(const ShadingRegion& g, const SyntheticGBuffer& gb, std::size_t i) {
  const glm::vec3 p(gb.position[4 * i], gb.position[4 * i + 1], gb.position[4 * i + 2]);
  const glm::vec3 n =
      glm::normalize(glm::vec3(gb.normal[4 * i], gb.normal[4 * i + 1], gb.normal[4 * i + 2]));
  return glm::all(glm::lessThanEqual(g.pMin, p)) && glm::all(glm::lessThanEqual(p, g.pMax)) &&
         glm::dot(n, g.axis) >= g.cosSpread;
}

// Cuts kept per cell from frame to frame (cuts/cell_cuts.h), while the view pans: every
// pixel lies in the region its cell's cut holds for, and every shared pixel stays within its
// cut's bound (the total rule's guarantee); a frame seen again keeps every cut, one panned a
// little keeps most, and another rule starts over.
TEST(TileCuts, KeptCellCutsHoldForEveryPixelAsTheViewMoves) {
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 1500, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CellCuts cells(cutter);
  const CutRule rule{0.02f, true, 8000};
  TileCuts before;
  for (const float pan : {0.0f, 0.0f, 0.05f, 0.6f, 2.0f}) {
    SCOPED_TRACE("pan " + std::to_string(pan));
    const SyntheticGBuffer g(pan);
    const TileCuts cuts = cells.cut(g.pixels(), rule, 2);
    EXPECT_GT(cells.cellSize(), 0.0f);
    const Checked c = checkCuts(g, lights, cuts);
    EXPECT_GT(c.sharedPixels, kSize * kSize / 2);
    EXPECT_EQ(c.failing, 0);
    EXPECT_LE(c.worstOverBound, 1.0001);
    EXPECT_EQ(c.mixedSurfaces, 0);
    int outside = 0;
    for (std::size_t i = 0; i < cuts.cutOfPixel.size(); ++i) {
      const std::uint32_t k = cuts.cutOfPixel[i];
      if (k < cells.frameCellCuts() && !regionHolds(cells.region(k), g, i)) ++outside;
    }
    EXPECT_EQ(outside, 0);
    if (pan == 0.0f && !before.texels.empty()) {  // the same frame again
      EXPECT_EQ(cuts.made, 0);
      EXPECT_EQ(cuts.texels.flat(), before.texels.flat());
      EXPECT_EQ(cuts.cutOfPixel, before.cutOfPixel);
    }
    if (pan == 0.05f) {  // a small pan: most cells keep their cuts
      EXPECT_GT(cuts.kept, 3 * cuts.made);
    }
    before = cuts;
  }
  const TileCuts other = cells.cut(SyntheticGBuffer(2.0f).pixels(), CutRule{0.05f, true, 8000}, 2);
  EXPECT_EQ(other.kept, 0);  // another ε: every cut anew
  EXPECT_GT(other.made, 0);
}

// Past the memory limit, the cells the last frame did not use are dropped (and found again if
// they come back into view); the last frame's stay.
TEST(TileCuts, PastTheLimitUnusedCellsAreDropped) {
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 500, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CellCuts cells(cutter, 1);  // any frame's cells exceed one word
  const CutRule rule{0.02f, true, 8000};
  const SyntheticGBuffer here(0.0f), there(3.0f);
  cells.cut(here.pixels(), rule, 2);
  const std::size_t first = cells.cellCount();
  EXPECT_EQ(cells.cut(here.pixels(), rule, 2).made, 0);  // over the limit, but all in use
  EXPECT_EQ(cells.cellCount(), first);
  const TileCuts seen = cells.cut(there.pixels(), rule, 2);
  EXPECT_GT(cells.cellCount(), first);
  EXPECT_EQ(cells.cut(there.pixels(), rule, 2).made, 0);  // drops the cells only `here` used
  EXPECT_EQ(cells.cellCount(), std::size_t(seen.made + seen.kept));
  const TileCuts back = cells.cut(here.pixels(), rule, 2);  // found again
  EXPECT_GT(back.made, 0);
  EXPECT_EQ(checkCuts(here, lights, back).failing, 0);
}

// A cell whose cut is full splits into eight smaller ones, twice at most; the pixels of a
// cell still full take squares' cuts for the frame, as render's frames have them, and all of
// them hold. (2,000 uniform lights under the total rule, at most 1,600 nodes: 65 cells' cuts
// fit, of 328 cells made, and one square's.)
TEST(TileCuts, FullCellsSplitThenFallBackToSquares) {
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 2000, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CellCuts cells(cutter);
  const SyntheticGBuffer g;
  const TileCuts cuts = cells.cut(g.pixels(), CutRule{0.02f, true, 1600}, 2);
  const Checked c = checkCuts(g, lights, cuts);
  EXPECT_GT(cells.cellCount(), 2 * cells.frameCellCuts());         // the split cells are kept
  EXPECT_GT(std::size_t(cuts.sharedCuts), cells.frameCellCuts());  // squares' cuts after cells'
  EXPECT_GT(c.sharedPixels, 1000);
  EXPECT_EQ(c.failing, 0);
  EXPECT_LE(c.worstOverBound, 1.0001);
}

// Under the node rule a cell keeps a cut larger than the frame's squares would before they
// split (splitCut): cut to that size, most of these cells' cuts fill up (27 of 32), yet none
// of the cells splits, and their pixels share their cuts. (20,000 mixed lights, ε = 0.02.)
TEST(TileCuts, UnderTheNodeRuleCellsKeepCutsPastTheSquaresSplit) {
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 20000, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  CellCuts cells(cutter);
  const SyntheticGBuffer g;
  const CutRule rule{0.02f, false, 8000};
  const TileCuts cuts = cells.cut(g.pixels(), rule, 2);
  EXPECT_EQ(cells.cellCount(), cells.frameCellCuts());  // no cell split
  CutRule squares = rule;
  squares.maxCut = splitCut(rule);
  squares.shareFull = false;
  int past = 0;
  for (std::size_t k = 0; k < cells.frameCellCuts(); ++k) {
    std::vector<std::uint32_t> entries;
    past += cutter.cutRegion(cells.region(k), squares, true, entries).perPixel ? 1 : 0;
  }
  std::cout << past << " of " << cells.frameCellCuts() << " cells' cuts pass " << squares.maxCut
            << " entries\n";
  EXPECT_GT(past, 0);
  EXPECT_GT(checkCuts(g, lights, cuts).sharedPixels, kSize * kSize / 2);
}

}  // namespace
}  // namespace manylight
