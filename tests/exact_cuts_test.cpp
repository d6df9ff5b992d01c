// Exact cuts (cuts/tile_cuts.h, RegionCut::exact) without GL: under the total rule, where the
// renderer lets pixels sum every light (CutRule::exactFull), a group whose cut fills up far
// from the rule gets a cut without entries, marked full, instead of the full cut.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "cuts/tile_cuts.h"
#include "generators/light_layouts.h"

namespace manylight {
namespace {

constexpr int kSize = 32;

// A floor (y = 0, facing up) filling the view, rows bottom-up as GL reads them.
struct Floor {
  std::vector<float> position, normal, specular;
  Floor() : position(kSize * kSize * 4), normal(kSize * kSize * 4), specular(kSize * kSize * 4) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const std::size_t i = (std::size_t(y) * kSize + x) * 4;
        position[i] = -3.0f + 6.0f * float(x) / kSize;
        position[i + 2] = -3.0f + 6.0f * float(y) / kSize;
        normal[i + 1] = normal[i + 3] = 1.0f;
      }
    }
  }
  GBufferPixels pixels() const {
    return {kSize, kSize, position.data(), normal.data(), specular.data()};
  }
};

struct FullCuts {
  int cuts = 0, empty = 0;  // full cuts, and those of them without entries
  int pixels = 0;           // pixels on full cuts
};

FullCuts fullCuts(const TileCuts& c) {
  FullCuts f;
  std::vector<bool> full(std::size_t(c.sharedCuts), false);
  const std::vector<std::uint32_t> texels = c.texels.flat();
  for (int k = 0; k < c.sharedCuts; ++k) {
    const std::uint32_t* header = texels.data() + 8 * std::size_t(k);
    if ((header[7] & kFullCutBit) == 0) continue;
    full[std::size_t(k)] = true;
    ++f.cuts;
    // No entries of any tree, none in a far field, nothing left out, no lobes; and the
    // next cut's entries start where its would.
    const std::size_t next = k + 1 < c.sharedCuts ? header[8] : texels.size() / 4;
    if (header[1] + header[2] + header[3] == 0 && header[7] == kFullCutBit && next == header[0])
      ++f.empty;
  }
  for (const std::uint32_t cut : c.cutOfPixel) f.pixels += cut != kNoSharedCut && full[cut];
  return f;
}

// 2,000 uniform lights, the total rule at ε = 0.02 with cuts of at most 400 entries: most
// groups' cuts fill up. Without exactFull they are shared full, with their entries; with it,
// each is exact: no entries, and its pixels sum every light in the shader. Pixels walk cuts of
// their own less (only where all five probed pixels meet the rule), so at least as many
// pixels are on exact cuts as were on full ones, and the frame's cuts take fewer texels.
// (Measured: 13 full cuts on 208 of the 1,024 pixels, the rest walking; 4 exact cuts, one a
// 16×16 quarter of the 1,024 pixels, in 8 texels instead of 10,426.)
TEST(ExactCuts, FullCutsBecomeExactWhereTheRendererAllowsIt) {
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 2000, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const Floor floor;
  CutRule rule{0.02f, true, 400};
  const TileCuts shared = cutter.cut(floor.pixels(), 16, rule, 2);
  rule.exactFull = true;
  const TileCuts exact = cutter.cut(floor.pixels(), 16, rule, 2);
  const FullCuts s = fullCuts(shared), e = fullCuts(exact);
  EXPECT_GT(s.cuts, 0);
  EXPECT_EQ(s.empty, 0);
  EXPECT_EQ(shared.exactCuts, 0);
  EXPECT_GT(e.cuts, 0);
  EXPECT_EQ(e.empty, e.cuts);
  EXPECT_EQ(exact.exactCuts, e.cuts);
  EXPECT_GE(e.pixels, s.pixels);
  EXPECT_LT(exact.texels.words(), shared.texels.words());
}

}  // namespace
}  // namespace manylight
