// The octree method against the reference: equal within float summation on ranged and mixed
// scenes, no light that reaches a pixel missing from its lists (a CPU brute-force count at
// every pixel), and no cap on a list's length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <iostream>
#include <random>

#include "generators/light_layouts.h"
#include "render/playback.h"
#include "render/render_job.h"
#include "scene/camera_animation.h"
#include "scene/gltf_loader.h"
#include "tests/gl_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

constexpr int kWidth = 96, kHeight = 72;
// Both methods sum the same terms in float, in different orders (measured: below 2e-6).
constexpr double kRelative = 1e-5;

const Scene& room() {
  context();
  return untexturedRoom();
}

struct Comparison {
  int pixels = 0, failing = 0;
  double worst = 0.0;
};

Comparison compare(const Image& image, const Image& reference) {
  Comparison c;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float* r = reference.pixel(x, y);
      const float* o = image.pixel(x, y);
      if (r[3] == 0.0f) continue;
      ++c.pixels;
      const double peak = std::max({double(r[0]), double(r[1]), double(r[2])});
      double diff = 0.0;
      for (int ch = 0; ch < 3; ++ch) diff = std::max(diff, std::abs(double(o[ch]) - double(r[ch])));
      const double rel = diff / std::max(peak, 1e-30);
      c.worst = std::max(c.worst, rel);
      if (diff > kRelative * peak + 1e-9) ++c.failing;
    }
  }
  return c;
}

struct OctreeRun {
  Comparison comparison;
  OctreeFrameStats stats;
  OctreeSummary octree;
  int passes = 0;
};

// `lights` in the room through the octree method and the reference, and the octree's lists
// at every pixel against every light.
OctreeRun run(const std::vector<Light>& lights, int entriesPerPass = 0) {
  Scene scene = room();
  scene.lights = lights;
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  const Image reference = renderScene(scene, request).image;
  request.method = Method::Octree;
  request.lightsPerPass = entriesPerPass;
  PreparedRender p(scene, request);
  FrameStats frame;
  const Image image = p.renderer->render(makeView(p.camera, kWidth, kHeight), p.settings, &frame);
  OctreeRun r;
  r.comparison = compare(image, reference);
  r.stats = p.renderer->octree()->frameStats(p.renderer->gbuffer(), true);
  r.octree = summarise(p.renderer->octree()->octree());
  r.passes = frame.lightingPasses;
  std::cout << lights.size() << " lights: " << r.comparison.pixels << " pixels, worst "
            << r.comparison.worst << ", entries " << r.stats.listEntries << ", evaluated "
            << r.stats.lightEvaluations << ", reaching " << r.stats.lightsReaching << ", lit "
            << r.stats.lightsLit << ", levels " << r.octree.levels << ", nodes " << r.octree.nodes
            << ", passes " << r.passes << "\n";
  return r;
}

void expectExact(const OctreeRun& r) {
  EXPECT_GT(r.comparison.pixels, kWidth * kHeight / 2);
  EXPECT_EQ(r.comparison.failing, 0) << "worst relative difference " << r.comparison.worst;
  EXPECT_EQ(r.stats.missed, 0);
}

// Tight: what the shader evaluates in full at most 1.5 times the lights whose window is
// non-zero, and the lists at most twice the lights that can light the pixel (range and cone).
void expectTight(const OctreeRun& r) {
  EXPECT_GT(r.stats.lightsLit, 10.0);
  EXPECT_LE(r.stats.lightEvaluations, 1.5 * r.stats.lightsReaching);
  EXPECT_LE(r.stats.listEntries, 2.0 * r.stats.lightsLit);
}

TEST(Octree, UniformRangedEqualsTheReference) {
  const OctreeRun r = run(layoutLights(LightLayout::UniformRanged, 4096, 7));
  expectExact(r);
  expectTight(r);
  EXPECT_EQ(r.octree.globalCount, 0u);
}

TEST(Octree, StreetRangedEqualsTheReference) {
  const OctreeRun r = run(layoutLights(LightLayout::StreetRanged, 4096, 7));
  expectExact(r);
  expectTight(r);
}

TEST(Octree, MixedWithUnrangedLightsEqualsTheReference) {
  // A third directional, half of the rest without a range: the global list.
  const OctreeRun r = run(layoutLights(LightLayout::Mixed, 3000, 7));
  expectExact(r);
  EXPECT_GT(r.octree.globalCount, 1000u);
}

TEST(Octree, NoLightsAndOneLight) {
  expectExact(run({}));
  Light one;
  one.position = {0.0f, 1.0f, 0.0f};
  one.range = 2.0f;
  one.intensity = 5.0f;
  expectExact(run({one}));
}

// `count` point lights within a centimetre of one point, each reaching 3 m: a leaf near it
// lists them all.
std::vector<Light> overlapping(int count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.005f, 0.005f);
  std::vector<Light> lights(static_cast<std::size_t>(count));
  for (Light& l : lights) {
    l.position = glm::vec3(0.5f, 1.0f, 0.5f) + glm::vec3(u(rng), u(rng), u(rng));
    l.range = 3.0f;
    l.intensity = 20.0f / float(count);
  }
  return lights;
}

TEST(Octree, TwentyThousandOverlappingLightsAreNotCapped) {
  const OctreeRun r = run(overlapping(20000));
  expectExact(r);
  EXPECT_EQ(r.octree.maxLeafCount, 20000u);
  EXPECT_GT(r.stats.lightsReaching, 4000.0);
}

TEST(Octree, ListsLongerThanAPassContinueInFurtherPasses) {
  // Passes of 3,000 entries: the 20,000 lights' lists take seven.
  const OctreeRun r = run(overlapping(20000), 3000);
  expectExact(r);
  EXPECT_EQ(r.passes, 7);
}

// Moved lights (Renderer::moveLights, the octree updated in place) against the reference of
// the same lights, frame after frame.
TEST(Octree, MovedLightsStayExact) {
  Scene scene = room();
  scene.lights = layoutLights(LightLayout::UniformRanged, 4096, 7);
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  request.method = Method::Octree;
  PreparedRender p(scene, request);
  const View view = makeView(p.camera, kWidth, kHeight);
  std::vector<Light> lights = scene.lights;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, int(lights.size()) - 1);
  std::uniform_real_distribution<float> step(-0.5f, 0.5f);
  for (int frame = 0; frame < 3; ++frame) {
    std::vector<int> changed;
    for (int k = 0; k < 400; ++k) changed.push_back(pick(rng));
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    for (int i : changed)
      lights[std::size_t(i)].position += glm::vec3(step(rng), step(rng), step(rng));
    p.renderer->moveLights(lights, changed, {});
    const Image image = p.renderer->render(view, p.settings);
    Scene moved = room();
    moved.lights = lights;
    RenderRequest reference = request;
    reference.method = Method::Reference;
    const Comparison c = compare(image, renderScene(moved, reference).image);
    EXPECT_EQ(c.failing, 0) << "frame " << frame << ", worst " << c.worst;
    EXPECT_EQ(p.renderer->octree()->frameStats(p.renderer->gbuffer(), true).missed, 0);
  }
}

// The shared AnimateAllTheThings asset plays its light animation: each frame as the
// reference renders the lights sampled at its time.
TEST(Octree, AnimateAllTheThingsPlaysItsLightAnimation) {
  const std::filesystem::path file = std::filesystem::path(MANYLIGHT_SHARED_SCENES) /
                                     "AnimateAllTheThings/24_animation_pointer.gltf";
  if (!std::filesystem::exists(file))
    GTEST_SKIP() << "no " << file << " (the shared scenes are absent)";
  context();
  const Scene scene = loadGltf(file.string());
  ASSERT_TRUE(scene.lightAnimation.animated());
  PlaybackRequest play;
  play.frame.width = kWidth;
  play.frame.height = kHeight;
  play.frame.method = Method::Octree;
  play.frames = 4;
  play.fps = 0.4f;  // frames at 0, 2.5, 5 and 7.5 s
  std::vector<Image> frames;
  const PlaybackOutcome out =
      manylight::play(scene, play, [&](int, const Image& image, const FrameStats&) {
        frames.push_back(image);
        return true;
      });
  EXPECT_TRUE(out.lightsAnimated);
  ASSERT_EQ(frames.size(), 4u);
  std::vector<Light> lights;
  int differing = 0;
  for (int i = 0; i < 4; ++i) {
    scene.lightAnimation.sampleLights(scene, float(i) / play.fps, lights);
    Scene at = scene;
    at.lights = lights;
    RenderRequest reference = play.frame;
    reference.method = Method::Reference;
    // The orbit the playback used for this frame: its camera.
    const Image expected = [&] {
      PreparedRender p(at, reference);
      Camera camera = p.camera;
      if (camera.animation.chain.empty()) {
        camera = orbitCamera(p.camera, 0.5f * (at.bounds().min + at.bounds().max),
                             glm::radians(play.orbitDegrees) * float(i) / 4.0f);
      } else {
        camera.world = animatedCameraWorld(p.camera, float(i) / play.fps);
      }
      return p.renderer->render(makeView(camera, kWidth, kHeight), p.settings);
    }();
    const Comparison c = compare(frames[std::size_t(i)], expected);
    EXPECT_EQ(c.failing, 0) << "frame " << i << ", worst " << c.worst;
    if (i > 0) differing += compare(frames[std::size_t(i)], frames[0]).failing > 0;
  }
  EXPECT_GT(differing, 0) << "the lights' animation changed nothing";
}

}  // namespace
}  // namespace manylight::testing
