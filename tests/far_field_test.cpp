// The far field of a shared cut (render/far_field.h), in double precision: a spot folded
// with its cone is its first-order expansion within the linearisation bound, and a far
// field moved to another centre is the same function.
#include "render/far_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/light_pack.h"
#include "render/node_lanes.h"
#include "tests/far_field_support.h"

namespace manylight {
namespace {

// A spot folded with its cone: the far field is its first-order expansion (error of
// second order, which a wrong Jacobian would not be) and within the linearisation bound.
TEST(FarField, SpotWithItsConeIsItsFirstOrderExpansion) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.3f, 3.0f, -0.2f};
  spot.outerConeAngle = 0.6f;
  spot.innerConeAngle = 0.3f;
  const glm::dvec3 c(0.9, 0.0, 0.0);
  // Pointing 0.45 rad away from c: c lies in the band between the cones.
  const glm::dvec3 w = glm::normalize(c - glm::dvec3(spot.position));
  const glm::dvec3 e = glm::normalize(glm::cross(w, glm::dvec3(0.0, 0.0, 1.0)));
  spot.direction = glm::vec3(std::cos(0.45) * w + std::sin(0.45) * e);
  spot.range = 6.0f;
  const SpotConeTerms cone = spotConeTerms(spot);
  const double t = glm::dot(glm::dvec3(spot.direction), w) * cone.scale + cone.offset;
  ASSERT_GT(t, 0.1);
  ASSERT_LT(t, 0.9);
  FarField far(c);
  far.addSpot(spot.position, 1.0f / (spot.range * spot.range),
              {spot.direction, cone.scale, cone.offset}, glm::vec3(1.0f));
  std::vector<std::uint32_t> words;
  far.write(words);
  const double h = 0.3;  // half-diagonal of the box the offsets stay in
  const glm::dvec3 boxMin = c - glm::dvec3(h / std::sqrt(3.0)), boxMax = 2.0 * c - boxMin;
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.1, 1.0, -0.2));
  // T over the box (per unit albedo and intensity, so times π per unit irradiance), with the
  // spot's cone (lane 0) and as a point light (lane 1): the cone's variation adds to it.
  RegionTerms region{};
  region.g.pMin = glm::vec3(boxMin);
  region.g.pMax = glm::vec3(boxMax);
  region.g.axis = glm::vec3(n);
  region.g.cosSpread = 1.0f;
  region.g.sinSpread = 0.0f;
  region.centre = 0.5f * (region.g.pMin + region.g.pMax);
  region.halfDiagonal = 0.5f * glm::length(region.g.pMax - region.g.pMin);
  region.h2 = region.halfDiagonal * region.halfDiagonal;
  FoldLanes in{};
  for (int l = 0; l < 2; ++l) {
    in.tree[l] = l == 0 ? 2.0f : 1.0f;
    for (int c = 0; c < 3; ++c) {
      in.repPoint[c][l] = spot.position[c];
      in.repAxis[c][l] = spot.direction[c];
    }
    in.repInvRange2[l] = 1.0f / (spot.range * spot.range);
    in.repCos[l] = std::cos(spot.outerConeAngle);
    in.coneScale[l] = cone.scale;
    in.coneOffset[l] = cone.offset;
  }
  float bounds[kLanes];
  foldBounds(region, in, 2, bounds);
  ASSERT_GT(bounds[1], 0.0f);
  ASSERT_GT(bounds[0], 1.5f * bounds[1]);
  const double bound = double(bounds[0]) * shading::kPi;
  for (const glm::dvec3 dir : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1),
                               glm::normalize(glm::dvec3(1, -1, 1))}) {
    for (const double delta : {1e-3, 0.1, h / std::sqrt(3.0)}) {
      const glm::dvec3 x = c + delta * dir;
      const double exact = unitRadiance(spot, x, n).x * shading::kPi;
      const double error = std::abs(farFieldIrradiance(words.data(), x, n).x - exact);
      // The remainder bound at distance δ, plus 1e-6 of the value: F and J are computed per
      // entry and stored in single precision.
      EXPECT_LE(error, bound * (delta * delta) / (h * h) + 1e-6 * exact) << delta;
    }
  }
}

// A far field moved to another centre (a seed's, for a smaller group) is the same linear
// function of the pixel.
TEST(FarField, MovedToAnotherCentreIsTheSameFunction) {
  FarField far(glm::vec3(0.5f, 0.0f, -0.25f));
  far.addPoint({0.3f, 2.0f, 0.1f}, 0.05f, {1.0f, 0.5f, 0.25f});
  far.addPoint({-1.5f, 1.0f, 2.0f}, 0.0f, {0.2f, 0.4f, 0.8f});
  far.addDirectional(glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)), {0.3f, 0.3f, 0.3f});
  const glm::vec3 centre(0.7f, 0.1f, -0.1f);
  const FarField moved = far.movedTo(centre);
  EXPECT_EQ(moved.count(), 3);
  std::vector<std::uint32_t> before, after;
  far.write(before);
  moved.write(after);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.1, 1.0, 0.05));
  for (const glm::dvec3 x : {glm::dvec3(centre), glm::dvec3(0.5, 0.0, -0.25),
                             glm::dvec3(0.9, -0.1, 0.0), glm::dvec3(0.6, 0.05, -0.3)}) {
    const glm::dvec3 a = farFieldIrradiance(before.data(), x, n);
    const glm::dvec3 b = farFieldIrradiance(after.data(), x, n);
    // Exact in double; 1e-5 of the value for F and J stored as floats.
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[ch], b[ch], 1e-5 * std::abs(a[ch]));
  }
  const glm::vec3 atCentre = moved.irradianceAtCentre(glm::vec3(n));
  const glm::dvec3 stored = farFieldIrradiance(after.data(), glm::dvec3(centre), n);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(atCentre[ch], stored[ch], 1e-5 * std::abs(stored[ch]));
}

}  // namespace
}  // namespace manylight
