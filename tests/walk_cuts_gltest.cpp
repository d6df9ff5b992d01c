// Pixels that walk their own cuts (glsl/lightcuts_walk.glsl): one that fills its cut falls
// back on the pass before, narrowed towards the finest threshold whose cut fits (its passes
// lower their threshold up to 32× at a time: narrowIfFull); spot nodes' cone factors bounded
// as the shared cuts bound them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "cuts/tile_cuts.h"
#include "generators/light_layouts.h"
#include "generators/scene_builder.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/gl_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

constexpr int kWidth = 96, kHeight = 72;

// The generated room without textures, lit by `count` lights of `layout` (seed 7).
Scene litRoom(LightLayout layout, int count) {
  context();
  RoomOptions o;
  o.lightCount = 1;
  o.textured = false;
  Scene scene = loadGltf(roomScene(o, "walk-cuts-room.gltf"));
  scene.lights = layoutLights(layout, count, 7);
  return scene;
}

RenderRequest request(Method method) {
  RenderRequest r;
  r.width = kWidth;
  r.height = kHeight;
  r.method = method;
  return r;
}

// A covered pixel's largest channel difference from the reference, and the reference's
// largest channel.
struct PixelError {
  double diff, peak;
};

// The errors of the covered pixels at the maximum cut (atMax) or below it.
std::vector<PixelError> pixelErrors(const RenderOutcome& out, const Image& reference, bool atMax) {
  std::vector<PixelError> errors;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float* r = reference.pixel(x, y);
      const float* c = out.image.pixel(x, y);
      if (r[3] == 0.0f || (out.frame.cuts.atMaxCut[std::size_t(y) * kWidth + x] != 0) != atMax)
        continue;
      PixelError e{0.0, std::max({double(r[0]), double(r[1]), double(r[2])})};
      for (int ch = 0; ch < 3; ++ch)
        e.diff = std::max(e.diff, std::abs(double(c[ch]) - double(r[ch])));
      errors.push_back(e);
    }
  }
  return errors;
}

// Per covered pixel at the maximum cut: its relative error, sorted.
std::vector<double> errorsAtTheMaximum(const RenderOutcome& out, const Image& reference) {
  std::vector<double> errors;
  for (const PixelError& e : pixelErrors(out, reference, true))
    errors.push_back(e.diff / std::max(e.peak, 1e-30));
  std::sort(errors.begin(), errors.end());
  return errors;
}

// Every pixel walks (no shared cuts) with room for 256 nodes, where ε = 0.005 asks for cuts
// of thousands: nearly every pixel fills its cut. The pass before the one that filled it was
// up to 32× coarser; narrowed, the pixels keep a pass within 2.4× of the finest that fits.
// Measured (4,096 mixed lights, 96×72, all 5,266 covered pixels at the maximum): median
// error 0.033, 90th percentile 0.076, worst 0.22; falling back on the pass before, 0.082,
// 0.19 and 0.49.
TEST(LightcutsWalks, AWalkThatFillsTheCutNarrowsItsThreshold) {
  const Scene scene = litRoom(LightLayout::Mixed, 4096);
  const Image reference = renderScene(scene, request(Method::Reference)).image;
  RenderRequest r = request(Method::Lightcuts);
  r.lightcuts.error = 0.005f;
  r.lightcuts.tileSize = 1;
  r.lightcuts.maxCut = 256;
  const RenderOutcome out = renderScene(scene, r);
  const std::vector<double> e = errorsAtTheMaximum(out, reference);
  ASSERT_FALSE(e.empty());
  const double median = e[e.size() / 2], p90 = e[e.size() * 9 / 10];
  std::cout << e.size() << " of " << out.frame.cuts.pixels << " pixels at the maximum, median "
            << median << ", 90th percentile " << p90 << ", worst " << e.back() << "\n";
  EXPECT_GT(e.size(), std::size_t(out.frame.cuts.pixels) * 9 / 10);
  EXPECT_LT(median, 0.05);
  EXPECT_LT(p90, 0.12);
  EXPECT_LT(e.back(), 0.35);
}

// A walk bounds a spot node's cone factor above and below as the shared cuts do
// (glsl/lightcuts_walk.glsl, spotConeFactor; cuts/lane_cones.h): under street lights (spots
// pointing down) with every pixel walking its own cut, fewer reach the maximum, and every
// pixel that does not is within ε of the reference (the total rule's guarantee: the bounds
// hold). With the cone factor taken as 1 and no lower bound, most reached the maximum.
// Measured (96×72, 5,266 covered pixels, total rule ε = 0.02): 1,511 and 1,998 at the maximum
// with 16,384 and 65,536 lights, against 2,999 and 3,112.
TEST(LightcutsWalks, AWalkBoundsSpotConesAsSharedCutsDo) {
  for (const int count : {16384, 65536}) {
    const Scene scene = litRoom(LightLayout::Street, count);
    const Image reference = renderScene(scene, request(Method::Reference)).image;
    RenderRequest r = request(Method::Lightcuts);
    r.lightcuts.mode = ErrorMode::Total;
    r.lightcuts.exactLimit = 0;  // no exact sums: pixels at the maximum keep their estimate
    r.lightcuts.tileSize = 1;    // every pixel walks its own cut
    const RenderOutcome out = renderScene(scene, r);
    const std::vector<PixelError> below = pixelErrors(out, reference, false);
    const int compared = int(below.size());
    const int failing = int(std::count_if(below.begin(), below.end(), [&](const PixelError& e) {
      return e.diff > (r.lightcuts.error + kFloatSlack) * e.peak + kAbsoluteFloor;
    }));
    const CutStats& cuts = out.frame.cuts;
    std::cout << count << " street lights: " << cuts.pixelsAtMaxCut << " of " << cuts.pixels
              << " pixels at the maximum; of the " << compared << " others " << failing
              << " off by more than ε\n";
    EXPECT_LT(cuts.pixelsAtMaxCut, cuts.pixels * 2 / 5) << count;
    EXPECT_EQ(compared + cuts.pixelsAtMaxCut, cuts.pixels) << count;
    EXPECT_EQ(failing, 0) << count;
  }
}

}  // namespace
}  // namespace manylight::testing
