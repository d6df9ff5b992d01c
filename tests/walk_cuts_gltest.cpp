// Pixels that walk their own cuts (glsl/lightcuts_walk.glsl): one that fills its cut falls
// back on the pass before, narrowed towards the finest threshold whose cut fits (its passes
// lower their threshold up to 32× at a time: narrowIfFull); and under the total rule a group's
// pixels walk only where probes bounded as their walks are meet the rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

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

// Per covered pixel at the maximum cut: the largest channel's difference over the largest
// reference channel.
std::vector<double> errorsAtTheMaximum(const RenderOutcome& out, const Image& reference) {
  std::vector<double> errors;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float* r = reference.pixel(x, y);
      const float* c = out.image.pixel(x, y);
      if (r[3] == 0.0f || !out.frame.cuts.atMaxCut[std::size_t(y) * kWidth + x]) continue;
      const double peak = std::max({double(r[0]), double(r[1]), double(r[2])});
      double diff = 0.0;
      for (int ch = 0; ch < 3; ++ch) diff = std::max(diff, std::abs(double(c[ch]) - double(r[ch])));
      errors.push_back(diff / std::max(peak, 1e-30));
    }
  }
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

// Under the total rule a group's pixels walk their own cuts only where probes bounded as a
// walk bounds (cuts/tile_cuts.h, CutRule::walkBounds: a spot node's cone factor 1, its lower
// bound 0) meet the rule. Under street lights (spots pointing down) most walks cannot: with
// every pixel walking, most reach the maximum. So the groups share their full cuts instead,
// for fewer node bounds a pixel and errors no larger. Measured (96×72, 5,266 covered pixels),
// 16,384 and 65,536 lights: 2,947 and 2,867 pixels share cuts, 1,277 and 1,714 node bounds a
// pixel against 1,940 and 2,881 with every pixel walking. With the shared cuts' cone bounds the
// probes met the rule: 1,499 and 1,264 shared, 2,177 and 3,138 node bounds a pixel.
TEST(LightcutsWalks, PixelsWalkOnlyWhereProbesBoundedAsWalksMeetTheRule) {
  for (const int count : {16384, 65536}) {
    const Scene scene = litRoom(LightLayout::Street, count);
    const Image reference = renderScene(scene, request(Method::Reference)).image;
    RenderRequest r = request(Method::Lightcuts);
    r.lightcuts.mode = ErrorMode::Total;
    r.lightcuts.exactLimit = 0;  // no exact sums: pixels at the maximum keep their estimate
    const RenderOutcome shared = renderScene(scene, r);
    r.lightcuts.tileSize = 1;  // every pixel walks its own cut
    const RenderOutcome walked = renderScene(scene, r);
    const std::vector<double> s = errorsAtTheMaximum(shared, reference);
    const std::vector<double> w = errorsAtTheMaximum(walked, reference);
    ASSERT_FALSE(s.empty() || w.empty()) << count;
    const double sharedP99 = s[s.size() * 99 / 100], walkedP99 = w[w.size() * 99 / 100];
    const CutStats &cuts = shared.frame.cuts, &walks = walked.frame.cuts;
    std::cout << count << " street lights: " << cuts.pixelsSharedCut << " of " << cuts.pixels
              << " pixels share cuts, " << cuts.nodeEvaluations << " node bounds a pixel, p99 "
              << sharedP99 << "; every pixel walking: " << walks.pixelsAtMaxCut
              << " at the maximum, " << walks.nodeEvaluations << ", p99 " << walkedP99 << "\n";
    EXPECT_GT(walks.pixelsAtMaxCut, walks.pixels / 2) << count;
    EXPECT_GT(cuts.pixelsSharedCut, cuts.pixels / 2) << count;
    EXPECT_LT(cuts.nodeEvaluations, 0.75 * walks.nodeEvaluations) << count;
    EXPECT_LE(sharedP99, walkedP99) << count;
  }
}

}  // namespace
}  // namespace manylight::testing
