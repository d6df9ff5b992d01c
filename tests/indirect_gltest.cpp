// `--indirect exact` (render/indirect_light.h) against a CPU double-precision one-bounce
// oracle in the Cornell-like room (generators/scene_builder.h): a convex room, so every wall
// point sees every other and the oracle needs no visibility. The oracle integrates, over the
// five walls, the light the spot's direct irradiance makes them reflect, by adaptive
// quadrature; the GPU sums the reflective shadow map's texels instead. Their difference is the
// map's own discretisation error, stated below.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>

#include "generators/scene_builder.h"
#include "render/gpu_scene.h"
#include "render/light_caches.h"
#include "render/render_job.h"
#include "render/rsm_choice.h"
#include "scene/shading_model.h"
#include "tests/gl_support.h"

namespace manylight::testing {
namespace {

constexpr int kWidth = 96, kHeight = 72;
constexpr double kPi = shading::kPi;

const Scene& cornell() {
  static const Scene scene = cornellWith(0);
  return scene;
}

// The room with 4,096 lights: its spot sends most, but not all, of the flux.
const Scene& cornell4096() {
  static const Scene scene = cornellWith(4095);
  return scene;
}

// ∫ over [s0, s1] × [t0, t1] of `wall` of the irradiance its reflected light gives x (normal
// n): M(y) · cos θx · cos θy / (π d²), M = albedo · the light's irradiance at y. Cells are
// split while they are large against their distance to x, then summed by 2 × 2 Gauss points.
glm::dvec3 integrate(const CornellWall& wall, const Light& light, glm::dvec3 x, glm::dvec3 n,
                     double s0, double s1, double t0, double t1, int depth) {
  const glm::dvec3 u(wall.u), v(wall.v), origin(wall.origin), nw(wall.normal);
  const glm::dvec3 centre = origin + 0.5 * (s0 + s1) * u + 0.5 * (t0 + t1) * v;
  const double size = std::max(glm::length(u) * (s1 - s0), glm::length(v) * (t1 - t0));
  if (depth < 16 && size > 0.2 * glm::length(centre - x)) {
    const double sm = 0.5 * (s0 + s1), tm = 0.5 * (t0 + t1);
    return integrate(wall, light, x, n, s0, sm, t0, tm, depth + 1) +
           integrate(wall, light, x, n, sm, s1, t0, tm, depth + 1) +
           integrate(wall, light, x, n, s0, sm, tm, t1, depth + 1) +
           integrate(wall, light, x, n, sm, s1, tm, t1, depth + 1);
  }
  const double g = 0.5 / std::sqrt(3.0);
  const double area = glm::length(glm::cross(u, v)) * (s1 - s0) * (t1 - t0) / 4.0;
  glm::dvec3 sum(0.0);
  for (double a : {0.5 - g, 0.5 + g}) {
    for (double b : {0.5 - g, 0.5 + g}) {
      const glm::dvec3 y = origin + (s0 + a * (s1 - s0)) * u + (t0 + b * (t1 - t0)) * v;
      const glm::dvec3 w = y - x;
      const double d2 = glm::dot(w, w);
      const double c = std::max(glm::dot(n, w), 0.0) * std::max(-glm::dot(nw, w), 0.0);
      if (c <= 0.0) continue;
      glm::dvec3 l;
      const glm::dvec3 m = glm::dvec3(wall.albedo) * shading::irradiance(light, y, nw, l);
      sum += m * (c / (kPi * d2 * d2)) * area;
    }
  }
  return sum;
}

glm::dvec3 oracleIrradiance(glm::dvec3 x, glm::dvec3 n, const Light& light) {
  glm::dvec3 e(0.0);
  for (const CornellWall& w : cornellWalls()) e += integrate(w, light, x, n, 0, 1, 0, 1, 0);
  return e;
}

struct Frame {
  Image image;
  FrameStats stats;
  std::vector<float> position, normal, albedo;  // the G-buffer, rows bottom-up
};

Frame render(const Scene& scene, Indirect mode, int rsmSize, bool shL2 = true,
             double leastShare = kRsmLeastShare) {
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  request.indirect.mode = mode;
  request.indirect.rsmSize = rsmSize;
  request.indirect.shL2 = shL2;
  request.indirect.rsmLeastShare = leastShare;
  PreparedRender p(scene, request);
  Frame f;
  f.image = p.renderer->render(makeView(p.camera, kWidth, kHeight), p.settings, &f.stats);
  f.position = p.renderer->gbuffer().read(GBuffer::kPosition);
  f.normal = p.renderer->gbuffer().read(GBuffer::kNormal);
  f.albedo = p.renderer->gbuffer().read(GBuffer::kAlbedo);
  return f;
}

double maxChannel(glm::dvec3 c) { return std::max({c.r, c.g, c.b}); }

struct Errors {
  std::vector<double> ofTotal, ofIndirect;  // |exact − oracle| per pixel over each
  double percentile(const std::vector<double>& v, double q) const {
    std::vector<double> s = v;
    std::sort(s.begin(), s.end());
    return s[std::size_t(q * double(s.size() - 1))];
  }
  double mean(const std::vector<double>& v) const {
    double sum = 0.0;
    for (double e : v) sum += e;
    return sum / double(v.size());
  }
};

// At every second pixel of every second row: the indirect radiance (exact − none) against
// the oracle's albedo/π · E.
Errors compareWithOracle(int rsmSize) {
  const Frame none = render(cornell(), Indirect::None, rsmSize);
  const Frame exact = render(cornell(), Indirect::Exact, rsmSize);
  Errors e;
  for (int y = 0; y < kHeight; y += 2) {
    for (int x = 0; x < kWidth; x += 2) {
      const std::size_t g = 4 * (std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x));
      if (exact.normal[g + 3] == 0.0f) continue;
      const glm::dvec3 p(exact.position[g], exact.position[g + 1], exact.position[g + 2]);
      const glm::dvec3 n(exact.normal[g], exact.normal[g + 1], exact.normal[g + 2]);
      const glm::dvec3 albedo(exact.albedo[g], exact.albedo[g + 1], exact.albedo[g + 2]);
      const glm::dvec3 oracle = albedo / kPi * oracleIrradiance(p, n, cornellSpot());
      const float* a = exact.image.pixel(x, y);
      const float* b = none.image.pixel(x, y);
      const glm::dvec3 total(a[0], a[1], a[2]);
      const glm::dvec3 indirect = total - glm::dvec3(b[0], b[1], b[2]);
      const double diff = maxChannel(glm::abs(indirect - oracle));
      e.ofTotal.push_back(diff / std::max(maxChannel(total), 1e-12));
      e.ofIndirect.push_back(diff / std::max(maxChannel(oracle), 1e-12));
    }
  }
  std::cout << "rsm " << rsmSize << ": " << e.ofTotal.size() << " pixels; of the total: mean "
            << e.mean(e.ofTotal) << ", p99 " << e.percentile(e.ofTotal, 0.99) << ", max "
            << e.percentile(e.ofTotal, 1.0) << "; of the indirect: median "
            << e.percentile(e.ofIndirect, 0.5) << ", p90 " << e.percentile(e.ofIndirect, 0.9)
            << ", p99 " << e.percentile(e.ofIndirect, 0.99) << "\n";
  return e;
}

// The map's discretisation error (docs/indirect.md): away from the edges where walls meet,
// about 1% of the indirect light at 64 × 64 texels; within a few texel footprints of such an
// edge the texels beside the pixel are too coarse, and the sum is up to 40% low there.
// Measured: at 32 × 32, mean 5.3% of the total, median 5.5% of the indirect; at 64 × 64,
// 1.2% and 0.94% (p90 2.0%); at 128 × 128, 1.0% and 0.90% (p90 1.6%).
TEST(Indirect, ExactMatchesTheOneBounceOracle) {
  const Errors coarse = compareWithOracle(32);
  const Errors e = compareWithOracle(IndirectSettings{}.rsmSize);
  ASSERT_GT(e.ofTotal.size(), 1000u);
  EXPECT_LT(e.mean(e.ofTotal), 0.02);
  EXPECT_LT(e.percentile(e.ofIndirect, 0.5), 0.02);
  EXPECT_LT(e.percentile(e.ofIndirect, 0.9), 0.04);
  // Finer maps converge on the oracle.
  EXPECT_LT(e.mean(e.ofTotal), 0.5 * coarse.mean(coarse.ofTotal));
}

// Mean of the indirect (exact − none) and total radiance over the floor pixels with
// x in [x0, x1].
struct FloorColour {
  glm::dvec3 indirect{0.0}, with{0.0}, without{0.0};
};
FloorColour floorColour(const Frame& none, const Frame& exact, double x0, double x1) {
  FloorColour c;
  int n = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t g = 4 * (std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x));
      if (exact.normal[g + 3] == 0.0f || exact.normal[g + 1] < 0.99f) continue;
      if (exact.position[g] < x0 || exact.position[g] > x1) continue;
      const float* a = exact.image.pixel(x, y);
      const float* b = none.image.pixel(x, y);
      c.with += glm::dvec3(a[0], a[1], a[2]);
      c.without += glm::dvec3(b[0], b[1], b[2]);
      ++n;
    }
  }
  c.indirect = (c.with - c.without) / double(std::max(n, 1));
  c.with /= double(std::max(n, 1));
  c.without /= double(std::max(n, 1));
  return c;
}

// The white floor beside the red wall turns red with indirect light, beside the green one
// green.
TEST(Indirect, ColourBleedsFromTheWallsOntoTheFloor) {
  const Frame none = render(cornell(), Indirect::None, 64);
  const Frame exact = render(cornell(), Indirect::Exact, 64);
  const FloorColour red = floorColour(none, exact, -1.0, -0.8);
  const FloorColour green = floorColour(none, exact, 0.8, 1.0);
  std::cout << "beside red: indirect " << red.indirect.r << " " << red.indirect.g << " "
            << red.indirect.b << "; beside green: " << green.indirect.r << " " << green.indirect.g
            << " " << green.indirect.b << "\n";
  EXPECT_GT(red.indirect.r, 1.5 * red.indirect.g);
  EXPECT_GT(green.indirect.g, 1.5 * green.indirect.r);
  EXPECT_GT(red.with.r / red.with.g, 1.05 * red.without.r / red.without.g);
  EXPECT_GT(green.with.g / green.with.r, 1.05 * green.without.g / green.without.r);
}

// With many lights, maps go to the spot and directional lights sending the most flux into
// the view, and --stats says what share of the flux they cover. A light sending under
// kRsmLeastShare of it gets none: of the room's 4,096 lights, only the spot.
TEST(Indirect, MapsGoToTheLightsWithTheMostFlux) {
  const Scene& scene = cornell4096();
  int candidates = 0;
  for (const Light& l : scene.lights) candidates += l.type != LightType::Point;
  const Frame all = render(scene, Indirect::Exact, 64, true, 0.0);
  EXPECT_EQ(all.stats.indirect.rsmLights, IndirectSettings{}.rsmLights);
  EXPECT_EQ(all.stats.indirect.candidates, candidates);
  EXPECT_EQ(all.stats.indirect.passes, IndirectSettings{}.rsmLights);
  EXPECT_EQ(all.stats.indirect.belowShare, 0);
  EXPECT_GT(all.stats.indirect.rsmTexels, 64 * 64);
  // The room's spot carries about two thirds of the flux; the other lights' share is small.
  EXPECT_GT(all.stats.indirect.fluxShare, 0.5);
  EXPECT_LT(all.stats.indirect.fluxShare, 0.95);
  const Frame f = render(scene, Indirect::Exact, 64);
  EXPECT_EQ(f.stats.indirect.rsmLights, 1);
  EXPECT_EQ(f.stats.indirect.passes, 1);
  EXPECT_EQ(f.stats.indirect.belowShare, IndirectSettings{}.rsmLights - 1);
  EXPECT_GT(f.stats.indirect.fluxShare, 0.5);
  EXPECT_LT(all.stats.indirect.fluxShare - f.stats.indirect.fluxShare, 3 * kRsmLeastShare);
  const Frame one = render(cornell(), Indirect::Exact, 64);
  EXPECT_EQ(one.stats.indirect.rsmLights, 1);
  EXPECT_DOUBLE_EQ(one.stats.indirect.fluxShare, 1.0);
}

// Where no light sends kRsmLeastShare of the view's flux (the room's 4,095 lights without its
// spot: about 1/4,095 each), no map is made and nothing is added: the frame is the one
// without indirect light, bit for bit.
TEST(Indirect, NoMapWhereNoLightSendsTheLeastShare) {
  Scene scene = cornell4096();
  ASSERT_EQ(scene.lights[0].type, LightType::Spot);
  scene.lights[0].intensity = 0.0f;  // the spot, cornellWith's first light
  const Frame none = render(scene, Indirect::None, 64);
  for (const Indirect mode : {Indirect::Exact, Indirect::Caches}) {
    const Frame f = render(scene, mode, 64);
    EXPECT_EQ(f.stats.indirect.rsmLights, 0);
    EXPECT_EQ(f.stats.indirect.belowShare, IndirectSettings{}.rsmLights);
    EXPECT_EQ(f.stats.indirect.caches, 0);
    EXPECT_EQ(f.stats.indirect.passes, 0);
    EXPECT_DOUBLE_EQ(f.stats.indirect.fluxShare, 0.0);
    EXPECT_EQ(f.image.rgba, none.image.rgba);
  }
}

// The map choice's measure (in float) reads, for a point or spot light of a range whose box
// holds few samples, only the samples in the grid cells the box overlaps: against every light
// summed at every sample (shading::irradiance, in double), each light's flux is within 10⁻⁶ of
// the largest, and the choice is the same. The scene's 4,096 lights have ranges from a few
// cells of the grid to the room's size.
TEST(Indirect, TheChoiceWeighsTheLightsAsTheShadingModelDoes) {
  const Scene& scene = cornell4096();
  const Frame f = render(scene, Indirect::None, 64);
  const RsmSamples samples = sampleRsmChoice(f.position, f.normal, scene.lights.size());
  ASSERT_GT(samples.position.size(), 200u);
  std::vector<double> oracle(scene.lights.size(), 0.0);
  double largest = 0.0;
  int reached = 0;  // lights of a range that light some samples but not all
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    int lit = 0;
    for (std::size_t s = 0; s < samples.position.size(); ++s) {
      glm::dvec3 l;
      const glm::dvec3 e = shading::irradiance(scene.lights[i], glm::dvec3(samples.position[s]),
                                               glm::dvec3(samples.normal[s]), l);
      oracle[i] += shading::luminance(e);
      lit += e != glm::dvec3(0.0);
    }
    reached += lit > 0 && std::size_t(lit) < samples.position.size() / 2 &&
               scene.lights[i].type != LightType::Directional;
    largest = std::max(largest, oracle[i]);
  }
  const std::vector<double> measured = measureLightFlux(scene.lights, samples);
  ASSERT_EQ(measured.size(), oracle.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < oracle.size(); ++i)
    worst = std::max(worst, std::abs(measured[i] - oracle[i]) / largest);
  std::cout << "largest flux " << largest << "; " << reached
            << " lights light under half the samples; worst light off by " << worst
            << " of the largest\n";
  EXPECT_GT(largest, 0.0);
  EXPECT_GT(reached, 100);
  EXPECT_LE(worst, 1e-6);
  EXPECT_EQ(chooseRsmLights(scene.lights, measured, 4).lights,
            chooseRsmLights(scene.lights, oracle, 4).lights);
}

// |caches − exact| per covered pixel over the pixel's total (direct + indirect) radiance:
// its mean and 99th percentile.
struct CacheError {
  double mean = 0.0, p99 = 0.0;
  long long nearClusters = 0;  // IndirectStats::nearClusters
};
CacheError cacheError(const Scene& scene, bool shL2, const char* name, int rsmSize = 64,
                      double leastShare = kRsmLeastShare) {
  const Frame exact = render(scene, Indirect::Exact, rsmSize, true, leastShare);
  const Frame caches = render(scene, Indirect::Caches, rsmSize, shL2, leastShare);
  // A pixel's total radiance, floored at 1% of the mean over the covered pixels: the edges of
  // the walls facing out of the room are black, and any error is infinite against 0 there.
  std::vector<double> diffs, totals;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t g = 4 * (std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x));
      if (exact.normal[g + 3] == 0.0f) continue;
      const float* a = exact.image.pixel(x, y);
      const float* b = caches.image.pixel(x, y);
      const glm::dvec3 total(a[0], a[1], a[2]);
      diffs.push_back(maxChannel(glm::abs(total - glm::dvec3(b[0], b[1], b[2]))));
      totals.push_back(maxChannel(total));
    }
  }
  double meanTotal = 0.0;
  for (double t : totals) meanTotal += t / double(totals.size());
  std::vector<double> errors;
  for (std::size_t i = 0; i < diffs.size(); ++i)
    errors.push_back(diffs[i] / std::max(totals[i], 0.01 * meanTotal));
  std::sort(errors.begin(), errors.end());
  CacheError e;
  for (double v : errors) e.mean += v / double(errors.size());
  e.p99 = errors[std::size_t(0.99 * double(errors.size() - 1))];
  e.nearClusters = caches.stats.indirect.nearClusters;
  std::cout << name << (shL2 ? " SH L2" : " SH L1") << ", " << rsmSize
            << "² maps: " << caches.stats.indirect.caches << " caches, " << e.nearClusters
            << " near clusters; |caches - exact| of the total: mean " << e.mean << ", p99 " << e.p99
            << ", max " << errors.back() << "\n";
  return e;
}

// docs/indirect.md's table, and the targets: mean ≤ 0.5%, 99th percentile ≤ 2% of the total.
// Measured: one spot, mean 0.38%, p99 1.86%; 65,536 lights (four maps), mean 0.20%, p99
// 0.88%. Every surface of the room faces along an axis, the centre of a normal bin
// (render/light_caches.h), so the caches' corrections hold all of the far field there and
// SH L1 and SH L2 come out the same.
TEST(Indirect, CachesMatchExact) {
  const CacheError l1 = cacheError(cornell(), false, "one spot");
  const CacheError l2 = cacheError(cornell(), true, "one spot");
  EXPECT_LT(l2.mean, 0.005);
  EXPECT_LT(l2.p99, 0.02);
  EXPECT_LT(l1.mean, 0.005);
  EXPECT_LT(l1.p99, 0.02);
  // Four maps, the spot's and three whose lights send under kRsmLeastShare of the flux.
  const CacheError m = cacheError(cornellWith(65535), true, "65,536 lights", 64, 0.0);
  EXPECT_LT(m.mean, 0.005);
  EXPECT_LT(m.p99, 0.02);
  // Texels a sixteenth the area: the near field reads clusters whole from 8 of their radii.
  const CacheError fine = cacheError(cornell(), true, "one spot", 256);
  EXPECT_GT(fine.nearClusters, 0);
  EXPECT_LT(fine.mean, 0.005);
  EXPECT_LT(fine.p99, 0.02);
}

// A static scene: a frame from a camera moved a little keeps the frame before's maps and its
// caches at the nodes both frames have, and comes out as a frame made afresh there; once the
// light moves, neither is kept, and the frame again matches one made afresh.
TEST(Indirect, KeptCachesMatchFreshOnes) {
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  request.indirect.mode = Indirect::Caches;
  PreparedRender p(cornell(), request);
  View view = makeView(p.camera, kWidth, kHeight);
  p.renderer->render(view, p.settings);
  view.eye += glm::vec3(0.05f, 0.02f, 0.0f);
  view.view = glm::lookAt(view.eye, view.eye + view.forward, glm::vec3(0, 1, 0));
  FrameStats kept, fresh;
  const Image moved = p.renderer->render(view, p.settings, &kept);
  PreparedRender q(cornell(), request);
  const Image afresh = q.renderer->render(view, q.settings, &fresh);
  std::cout << kept.indirect.cachesKept << " of " << kept.indirect.caches
            << " caches kept; largest difference " << largestDifference(moved, afresh) << "\n";
  EXPECT_TRUE(kept.indirect.mapsKept);
  EXPECT_FALSE(fresh.indirect.mapsKept);
  EXPECT_EQ(fresh.indirect.cachesKept, 0);
  EXPECT_EQ(kept.indirect.caches, fresh.indirect.caches);
  EXPECT_GT(kept.indirect.cachesKept, kept.indirect.caches / 2);
  EXPECT_LT(kept.indirect.cachesKept, kept.indirect.caches);
  EXPECT_LE(largestDifference(moved, afresh), 1e-5);

  Scene changed = cornell();
  changed.lights[0].position.x += 0.1f;
  p.renderer->moveLights(changed.lights, {0}, BakeOptions{});
  FrameStats relit;
  const Image lit = p.renderer->render(view, p.settings, &relit);
  PreparedRender r(changed, request);
  const Image litAfresh = r.renderer->render(view, r.settings);
  EXPECT_FALSE(relit.indirect.mapsKept);
  EXPECT_EQ(relit.indirect.cachesKept, 0);
  EXPECT_LE(largestDifference(lit, litAfresh), 1e-5);
  EXPECT_GT(largestDifference(lit, moved), 1e-3);

  // An `exact` frame with the light back where it was makes the maps anew; the caches frame
  // after it keeps those maps, but not the caches gathered from the moved light's.
  p.renderer->moveLights(cornell().lights, {0}, BakeOptions{});
  FrameSettings exact = p.settings;
  exact.indirect.mode = Indirect::Exact;
  p.renderer->render(view, exact);
  FrameStats back;
  const Image returned = p.renderer->render(view, p.settings, &back);
  EXPECT_TRUE(back.indirect.mapsKept);
  EXPECT_EQ(back.indirect.cachesKept, 0);
  EXPECT_LE(largestDifference(returned, afresh), 1e-5);
}

// An orthographic camera moved one pixel to the right per frame: each pixel sees the point
// its right-hand neighbour saw the frame before. Caches sit at world-space nodes, so where
// the point keeps its cascade it gets the same caches and the same value; in a transition
// band the blend moves with the camera.
TEST(Indirect, CachesStayPutAsTheCameraMoves) {
  RenderRequest request;
  request.width = kWidth;
  request.height = kHeight;
  request.indirect.mode = Indirect::Caches;
  PreparedRender p(cornell(), request);
  const float pixel = 2.4f / float(kWidth);
  View view;
  view.orthographic = true;
  // Looking down and to the left, so the floor, the right wall and the back wall show.
  view.forward = glm::normalize(glm::vec3(-0.3f, -0.4f, -1.0f));
  const glm::vec3 right = glm::normalize(glm::cross(view.forward, glm::vec3(0, 1, 0)));
  view.projection = glm::ortho(-1.2f, 1.2f, -0.9f, 0.9f, 0.1f, 10.0f);
  double outside = 0.0, inside = 0.0;
  long long compared = 0, banded = 0;
  Image before;
  std::vector<float> beforePosition;
  for (int frame = 0; frame < 60; ++frame) {
    view.eye = glm::vec3(0.9f, 2.2f, 4.0f) + float(frame) * pixel * right;
    view.view = glm::lookAt(view.eye, view.eye + view.forward, glm::vec3(0, 1, 0));
    const Image image = p.renderer->render(view, p.settings);
    const std::vector<float> position = p.renderer->gbuffer().read(GBuffer::kPosition);
    const std::vector<float> normal = p.renderer->gbuffer().read(GBuffer::kNormal);
    const CacheGrid grid = frameCacheGrid(p.settings.indirect, cornell().bounds(), view.eye);
    const CacheGrid last =
        frameCacheGrid(p.settings.indirect, cornell().bounds(), view.eye - pixel * right);
    double mean = 0.0;
    int covered = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      if (image.rgba[i + 3] == 0.0f) continue;
      mean += std::max({image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]});
      ++covered;
    }
    mean /= double(std::max(covered, 1));
    for (int y = 0; frame > 0 && y < kHeight; ++y) {
      for (int x = 0; x + 1 < kWidth; ++x) {
        const std::size_t g = 4 * (std::size_t(kHeight - 1 - y) * kWidth + std::size_t(x));
        const std::size_t h = g + 4;  // the pixel to the right, the frame before
        if (normal[g + 3] == 0.0f) continue;
        const glm::vec3 a(position[g], position[g + 1], position[g + 2]);
        const glm::vec3 b(beforePosition[h], beforePosition[h + 1], beforePosition[h + 2]);
        if (glm::length(a - b) > 2e-6f) continue;  // not the same point
        // The walls' outer faces: black but for caches' light leaking through the walls.
        if (glm::any(glm::greaterThan(glm::abs(a - glm::vec3(0, 1, 0)), glm::vec3(1.0001f))))
          continue;
        float bandNow = 0.0f, bandBefore = 0.0f;
        const int k = cascadeOf(grid, a, &bandNow), j = cascadeOf(last, b, &bandBefore);
        const float* u = image.pixel(x, y);
        const float* v = before.pixel(x + 1, y);
        // Floored at 1% of the frame's mean over covered pixels (of their largest channel), as
        // in cacheError: the walls' outer faces are black but for light leaking through.
        const double peak = std::max({double(u[0]), double(u[1]), double(u[2]), 0.01 * mean});
        double change = 0.0;
        for (int c = 0; c < 3; ++c)
          change = std::max(change, std::abs(double(u[c]) - double(v[c])));
        if (k == j && bandNow == 0.0f && bandBefore == 0.0f) {
          outside = std::max(outside, change / peak);
          ++compared;
        } else {
          inside = std::max(inside, change / peak);
          ++banded;
        }
      }
    }
    before = image;
    beforePosition = position;
  }
  std::cout << compared << " pixel pairs outside bands: largest change " << outside << "; "
            << banded << " in bands: " << inside << "\n";
  EXPECT_GT(compared, 59 * kWidth * kHeight / 4);
  EXPECT_GT(banded, 0);
  EXPECT_LE(outside, 1e-4);
  EXPECT_LE(inside, 0.01);
}

}  // namespace
}  // namespace manylight::testing
