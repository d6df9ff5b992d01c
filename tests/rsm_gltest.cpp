// Parts of `--indirect` that need no context (built with the GL tests, since they link
// render/): the map choice's rule and measure, the map clusters and the caches' normal bins.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/light_caches.h"
#include "render/rsm_choice.h"
#include "render/rsm_clusters.h"
#include "scene/shading_model.h"

namespace manylight::testing {
namespace {

// The frame before's lights keep their maps, in their order, while their flux is at least
// kRsmChoiceKeep × the weakest of the largest; a point light never gets one.
TEST(Indirect, TheChoiceKeepsTheLightsOfTheFrameBefore) {
  std::vector<Light> lights(6);
  for (Light& l : lights) l.type = LightType::Spot;
  lights[5].type = LightType::Point;
  const std::vector<double> flux = {10.0, 8.0, 3.0, 5.0, 2.0, 50.0};
  EXPECT_EQ(chooseRsmLights(lights, flux, 2).lights, (std::vector<int>{0, 1}));
  // 5 ≥ 0.5 × 8 stays, first; 2 < 4 gives way to the largest, 0.
  EXPECT_EQ(chooseRsmLights(lights, flux, 2, {3, 4}).lights, (std::vector<int>{3, 0}));
  EXPECT_EQ(chooseRsmLights(lights, flux, 2, {1, 0}).lights, (std::vector<int>{1, 0}));
  EXPECT_EQ(chooseRsmLights(lights, flux, 2, {5, 4}).lights, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(fluxShare(chooseRsmLights(lights, flux, 2, {3, 4}).lights, flux), 15.0 / 78.0);
  EXPECT_EQ(chooseRsmLights(lights, flux, 2, {3, 3}).lights, (std::vector<int>{3, 0}));
}

// A light sending under `leastShare` of every light's flux (points too) gets no map, whatever
// its rank, unless the frame before's choice had it and it sends at least kRsmChoiceKeep ×
// that; RsmChoice::belowShare counts the largest passed over. A view that receives no flux at
// all keeps the ranking's lights, and a NaN flux passes over every light but at share 0.
TEST(Indirect, TheChoicePassesOverLightsUnderTheLeastShare) {
  std::vector<Light> lights(6);
  for (Light& l : lights) l.type = LightType::Spot;
  lights[5].type = LightType::Point;
  const std::vector<double> flux = {10.0, 8.0, 3.0, 5.0, 2.0, 50.0};  // Σ 78
  RsmChoice c = chooseRsmLights(lights, flux, 3, {}, 0.1);            // at least 7.8
  EXPECT_EQ(c.lights, (std::vector<int>{0, 1}));
  EXPECT_EQ(c.belowShare, 1);
  // A light of the frame before keeps its map down to kRsmChoiceKeep × the least share (3.9).
  c = chooseRsmLights(lights, flux, 3, {3, 1}, 0.1);
  EXPECT_EQ(c.lights, (std::vector<int>{3, 1, 0}));
  EXPECT_EQ(c.belowShare, 0);
  c = chooseRsmLights(lights, flux, 3, {2, 1}, 0.1);
  EXPECT_EQ(c.lights, (std::vector<int>{1, 0}));
  EXPECT_EQ(c.belowShare, 1);
  c = chooseRsmLights(lights, flux, 2, {}, 0.2);  // at least 15.6: none
  EXPECT_TRUE(c.lights.empty());
  EXPECT_EQ(c.belowShare, 2);
  c = chooseRsmLights(lights, flux, 2, {0}, 0.2);  // 10 ≥ 7.8 keeps its map
  EXPECT_EQ(c.lights, (std::vector<int>{0}));
  EXPECT_EQ(c.belowShare, 1);
  c = chooseRsmLights(lights, flux, 3, {}, 0.0);
  EXPECT_EQ(c.lights, (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(c.belowShare, 0);
  c = chooseRsmLights(lights, std::vector<double>(6, 0.0), 2, {}, 0.1);
  EXPECT_EQ(c.lights, (std::vector<int>{0, 1}));
  EXPECT_EQ(c.belowShare, 0);
  std::vector<double> nan = flux;
  nan[5] = std::numeric_limits<double>::quiet_NaN();  // the point light
  EXPECT_TRUE(chooseRsmLights(lights, nan, 2, {}, 0.1).lights.empty());
  EXPECT_EQ(chooseRsmLights(lights, nan, 2, {}, 0.0).lights, (std::vector<int>{0, 1}));
}

// The choice's measure against a double-precision sum of shading::irradiance at every sample,
// where its grid over the samples meets its edges: a light of small range in a corner, a range
// past the int's count of cells (read as every sample, as no range is), samples all at one
// point (one cell of no size), and none.
TEST(Indirect, TheChoiceMeasureHoldsAtItsGridsEdges) {
  RsmSamples floor;
  for (int i = 0; i < 256; ++i) {
    floor.position.push_back(glm::vec3(float(i % 16), 0.0f, float(i / 16)));
    floor.normal.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
  }
  std::vector<Light> lights(5);
  for (Light& l : lights) {
    l.type = LightType::Point;
    l.position = glm::vec3(7.5f, 2.0f, 7.5f);
    l.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  }
  lights[0].range = 1e10f;
  lights[1].range = 0.0f;
  lights[2] = {LightType::Spot,
               glm::vec3(0.2f, 0.5f, 0.3f),
               glm::vec3(0.0f, -1.0f, 0.0f),
               glm::vec3(1.0f),
               3.0f,
               1.5f,
               0.2f,
               1.2f};
  lights[3].type = LightType::Directional;
  lights[4].range = 4.0f;
  const auto oracle = [&](const Light& light, const RsmSamples& samples) {
    double sum = 0.0;
    for (std::size_t s = 0; s < samples.position.size(); ++s) {
      glm::dvec3 l;
      const glm::dvec3 e = shading::irradiance(light, glm::dvec3(samples.position[s]),
                                               glm::dvec3(samples.normal[s]), l);
      sum += shading::luminance(e);
    }
    return sum;
  };
  RsmSamples one;
  one.position.assign(3, glm::vec3(0.3f, 0.0f, 0.4f));
  one.normal.assign(3, glm::vec3(0.0f, 1.0f, 0.0f));
  for (const RsmSamples* samples : {&floor, &one}) {
    const std::vector<double> flux = measureLightFlux(lights, *samples);
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const double expected = oracle(lights[i], *samples);
      if (samples == &floor) {
        EXPECT_GT(expected, 0.0) << "light " << i;
      }
      EXPECT_NEAR(flux[i], expected, 1e-6 * expected) << "light " << i;
    }
  }
  EXPECT_EQ(measureLightFlux(lights, RsmSamples{}), std::vector<double>(5, 0.0));
}

// A light's mean weighs each frame's flux kRsmChoiceMemory^age, until the light changes: then
// it starts again from that frame's flux, the others' going on. fluxShare is the chosen
// lights' part of a flux's sum.
TEST(Indirect, TheChoiceRanksByTheFluxOfTheLastFrames) {
  std::vector<Light> lights(3);
  for (Light& l : lights) l.type = LightType::Spot;
  RsmFluxHistory history;
  EXPECT_EQ(history.add(lights, {4.0, 0.0, 1.0}), (std::vector<double>{4.0, 0.0, 1.0}));
  const std::vector<double> second = history.add(lights, {0.0, 2.0, 1.0});
  const double m = kRsmChoiceMemory;
  EXPECT_DOUBLE_EQ(second[0], 4.0 * m / (m + 1.0));
  EXPECT_DOUBLE_EQ(second[1], 2.0 / (m + 1.0));
  EXPECT_DOUBLE_EQ(second[2], 1.0);
  // Light 0, out of this frame's samples, keeps its map over light 1.
  EXPECT_EQ(chooseRsmLights(lights, second, 1, {0}).lights, (std::vector<int>{0}));
  lights[2].intensity = 2.0f;
  const std::vector<double> third = history.add(lights, {0.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(third[0], 4.0 * m * m / (m * m + m + 1.0));
  EXPECT_DOUBLE_EQ(third[1], (2.0 * m + 2.0) / (m * m + m + 1.0));
  EXPECT_DOUBLE_EQ(third[2], 3.0);
  lights.pop_back();
  EXPECT_EQ(history.add(lights, {1.0, 0.0}), (std::vector<double>{1.0, 0.0}));
  EXPECT_DOUBLE_EQ(fluxShare({1}, {0.0, 2.0, 1.0}), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(fluxShare({1}, {0.0, 0.0, 0.0}), 1.0);
}

// Over a playback (RsmFluxHistory::due) a light is measured every kRsmChoiceStride frames in
// turn, and at once when it changes; one not measured keeps its mean, one measured in turn
// weighs its mean kRsmChoiceMemory^kRsmChoiceStride; measureLightFlux leaves the others out.
TEST(Indirect, TheChoiceMeasuresTheLightsInTurn) {
  std::vector<Light> lights(6);
  for (Light& l : lights) l.type = LightType::Spot;
  RsmFluxHistory history;
  std::vector<char> due = history.due(lights);
  EXPECT_EQ(due, std::vector<char>(6, 1));  // no means yet
  history.add(lights, {1.0, 2.0, 3.0, 4.0, 5.0, 6.0}, &due);
  EXPECT_EQ(history.due(lights), (std::vector<char>{0, 1, 0, 0, 0, 1}));
  lights[3].intensity = 2.0f;
  due = history.due(lights);
  EXPECT_EQ(due, (std::vector<char>{0, 1, 0, 1, 0, 1}));
  const std::vector<double> means = history.add(lights, {0.0, 4.0, 0.0, 8.0, 0.0, 2.0}, &due);
  const double k = std::pow(kRsmChoiceMemory, double(kRsmChoiceStride));
  EXPECT_DOUBLE_EQ(means[0], 1.0);
  EXPECT_DOUBLE_EQ(means[1], (2.0 * k + 4.0) / (k + 1.0));
  EXPECT_DOUBLE_EQ(means[2], 3.0);
  EXPECT_DOUBLE_EQ(means[3], 8.0);  // changed: starts again
  EXPECT_DOUBLE_EQ(means[5], (6.0 * k + 2.0) / (k + 1.0));
  EXPECT_EQ(history.due(lights), (std::vector<char>{0, 0, 1, 0, 0, 0}));  // the next turn
  RsmSamples below;
  below.position.assign(2, glm::vec3(0.0f, 0.0f, -1.0f));
  below.normal.assign(2, glm::vec3(0.0f, 0.0f, 1.0f));
  const std::vector<double> all = measureLightFlux(lights, below);
  const std::vector<double> some = measureLightFlux(lights, below, &due);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    EXPECT_GT(all[i], 0.0);
    EXPECT_EQ(some[i], due[i] ? all[i] : 0.0) << "light " << i;
  }
}

// An 8 × 8 map: the lower-left block flat on z = 0 with equal flux, the lower-right one
// with its right half facing +x, the top two reflecting nothing but one texel.
TEST(Indirect, ClustersHoldTheirTexels) {
  const int size = 8;
  std::vector<float> position(4 * size * size, 0.0f), normal(position.size(), 0.0f),
      flux(position.size(), 0.0f);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t t = 4 * std::size_t(y * size + x);
      if (y >= 4 && !(x == 6 && y == 7)) continue;
      const bool folded = x >= 6;
      position[t] = float(x);
      position[t + 1] = float(y);
      normal[t + 2] = folded ? 0.0f : 1.0f;
      normal[t] = folded ? 1.0f : 0.0f;
      flux[t] = flux[t + 1] = flux[t + 2] = 1.0f;
      flux[t + 3] = 0.5f;
    }
  const RsmClusters c = clusterRsm(position, normal, flux, size);
  ASSERT_EQ(c.size, 2);
  // The flat block: centre (1.5, 1.5, 0), radius the half diagonal, 16 texels' flux.
  EXPECT_FLOAT_EQ(c.centre[0].x, 1.5f);
  EXPECT_FLOAT_EQ(c.centre[0].y, 1.5f);
  EXPECT_NEAR(c.centre[0].w, 1.5f * std::sqrt(2.0f), 1e-5f);
  EXPECT_EQ(c.normal[0], glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
  EXPECT_EQ(c.flux[0], glm::vec4(16.0f, 16.0f, 16.0f, 0.5f));
  // The folded block: half its texels face +z, half +x: not flat.
  EXPECT_EQ(c.normal[1].w, 0.0f);
  EXPECT_NEAR(glm::length(glm::vec3(c.normal[1])), 1.0f, 1e-5f);
  // Nothing reflects in the top-left block; one texel in the top-right.
  EXPECT_LT(c.centre[2].w, 0.0f);
  EXPECT_EQ(c.flux[2], glm::vec4(0.0f));
  EXPECT_EQ(c.centre[3], glm::vec4(6.0f, 7.0f, 0.0f, 0.0f));
  EXPECT_EQ(c.flux[3], glm::vec4(1.0f, 1.0f, 1.0f, 0.5f));
}

// Every bin's centre falls in that bin, the axes are centres, and a normal lies within the
// widest bin's reach of its bin's centre.
TEST(Indirect, NormalBinsHoldTheirCentres) {
  constexpr int bins = 6 * kNormalBinGrid * kNormalBinGrid;
  for (int b = 0; b < bins; ++b) EXPECT_EQ(normalBin(binNormal(b)), b) << b;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      EXPECT_EQ(binNormal(normalBin(n)), n);
    }
  }
  float least = 1.0f;
  for (int i = 0; i < 2000; ++i) {
    const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 2000.0f, phi = 2.39996323f * float(i);
    const float r = std::sqrt(1.0f - z * z);
    const glm::vec3 n(r * std::cos(phi), r * std::sin(phi), z);
    least = std::min(least, glm::dot(n, binNormal(normalBin(n))));
  }
  EXPECT_GT(least, 0.8f);
}

// Pixels spread over more nodes than the budget: the allocation stops at kMaxCaches and counts
// what it refused.
TEST(Indirect, CachesStopAtTheBudget) {
  const CacheGrid grid = cacheGrid(glm::vec3(0.0f), 1.0f, 1);
  const int side = 100;  // 100 × 100 pixels on each of 10 planes, one a cell apart
  std::vector<float> position, normal;
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        position.insert(position.end(), {float(x - 50) * 0.6f + 0.1f, float(y - 50) * 0.6f + 0.1f,
                                         float(z - 5) * 6.0f + 0.1f, 0.0f});
        normal.insert(normal.end(), {0.0f, 0.0f, 1.0f, 1.0f});
      }
  const CacheAllocation few = allocateCaches(grid, position, normal);
  EXPECT_EQ(few.refused, 0);
  EXPECT_LT(few.positions.size(), kMaxCaches);
  // Each node of a pixel with the normal of every bin in turn: 54 caches a node.
  std::vector<float> turned = normal;
  for (std::size_t i = 0; i < turned.size() / 4; ++i) {
    const glm::vec3 n = binNormal(int(i % 54));
    turned[4 * i] = n.x;
    turned[4 * i + 1] = n.y;
    turned[4 * i + 2] = n.z;
  }
  const CacheAllocation many = allocateCaches(grid, position, turned);
  EXPECT_EQ(many.positions.size(), kMaxCaches);
  EXPECT_GT(many.refused, 0);
}

// An allocation made into one that held the last frame's caches (its CAV rewritten to slots,
// as LightCaches::upload does), for cascades moved with the camera, is the one made afresh.
TEST(Indirect, AnAllocationReusedMatchesAFreshOne) {
  std::vector<float> position, normal;
  for (int i = 0; i < 4000; ++i) {
    const float t = float(i);
    position.insert(position.end(), {std::sin(t) * 3.0f, std::cos(0.7f * t) * 2.0f,
                                     std::sin(1.3f * t) * 4.0f, 0.0f});
    const glm::vec3 n = i % 3 == 0 ? glm::vec3(0, 1, 0) : glm::normalize(glm::vec3(1, t, 2));
    normal.insert(normal.end(), {n.x, n.y, n.z, i % 17 == 0 ? 0.0f : 1.0f});
  }
  const CacheGrid before = cacheGrid(glm::vec3(0.0f), 0.25f, 2);
  const CacheGrid after = cacheGrid(glm::vec3(0.37f, -0.2f, 0.11f), 0.25f, 2);
  ASSERT_EQ(before.nodesPerAxis(), after.nodesPerAxis());
  CacheAllocation reused = allocateCaches(before, position, normal);
  ASSERT_GT(reused.nodes.size(), 100u);
  const float caches = float(reused.positions.size());
  for (std::size_t node : reused.nodes) reused.cav[node] = caches - 1.0f - reused.cav[node];
  allocateCaches(after, position, normal, reused);
  const CacheAllocation fresh = allocateCaches(after, position, normal);
  EXPECT_EQ(reused.cav, fresh.cav);
  EXPECT_EQ(reused.positions, fresh.positions);
  EXPECT_EQ(reused.normals, fresh.normals);
  EXPECT_EQ(reused.next, fresh.next);
  EXPECT_EQ(reused.nodes, fresh.nodes);
  EXPECT_EQ(reused.classes, fresh.classes);
  EXPECT_EQ(reused.refused, fresh.refused);
}

}  // namespace
}  // namespace manylight::testing
