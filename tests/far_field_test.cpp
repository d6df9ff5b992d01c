// The far field of a shared cut (cuts/far_field.h), in double precision: a spot folded
// with its cone is its first-order expansion within the linearisation bound, entries folded
// into it stay within their bound at points of the region, a light whose range sphere cuts
// the region never folds, and a far field moved to another centre is the same function.
#include "cuts/far_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bake/light_pack.h"
#include "cuts/node_lanes.h"
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

// The region of the box [lo, hi] whose normals lie within `spread` radians of `axis`.
RegionTerms regionOf(glm::vec3 lo, glm::vec3 hi, glm::vec3 axis, float spread) {
  RegionTerms r{};
  r.g.pMin = lo;
  r.g.pMax = hi;
  r.g.axis = axis;
  r.g.cosSpread = std::cos(spread);
  r.g.sinSpread = std::sin(spread);
  r.centre = 0.5f * (lo + hi);
  r.halfDiagonal = 0.5f * glm::length(hi - lo);
  r.h2 = 0.25f * glm::dot(hi - lo, hi - lo);
  return r;
}

// A point or spot light as an entry of lane 0 of `in`, as cuts/cut_region.cpp fills it.
void setEntry(FoldLanes& in, const Light& light) {
  in.tree[0] = light.type == LightType::Spot ? 2.0f : 1.0f;
  for (int c = 0; c < 3; ++c) {
    in.repPoint[c][0] = light.position[c];
    in.repAxis[c][0] = light.direction[c];
  }
  in.repInvRange2[0] = light.range > 0.0f ? 1.0f / (light.range * light.range) : 0.0f;
  in.repCos[0] = std::cos(light.outerConeAngle);
  const SpotConeTerms cone = spotConeTerms(light);
  in.coneScale[0] = light.type == LightType::Spot ? cone.scale : 0.0f;
  in.coneOffset[0] = light.type == LightType::Spot ? cone.offset : 0.0f;
}

// The texels of a far field about `centre` holding `light` at unit intensity.
std::vector<std::uint32_t> farFieldOf(const Light& light, glm::vec3 centre) {
  FarField far(centre);
  const float invRange2 = light.range > 0.0f ? 1.0f / (light.range * light.range) : 0.0f;
  if (light.type == LightType::Spot) {
    const SpotConeTerms cone = spotConeTerms(light);
    far.addSpot(light.position, invRange2, {light.direction, cone.scale, cone.offset},
                glm::vec3(1.0f));
  } else {
    far.addPoint(light.position, invRange2, glm::vec3(1.0f));
  }
  std::vector<std::uint32_t> words;
  far.write(words);
  return words;
}

// The nearest and farthest squared distances from `p` to the box [lo, hi], in double.
glm::dvec2 distances2(glm::dvec3 p, glm::dvec3 lo, glm::dvec3 hi) {
  const glm::dvec3 nearest = glm::clamp(p, lo, hi) - p;
  const glm::dvec3 farthest = glm::max(glm::abs(lo - p), glm::abs(hi - p));
  return {glm::dot(nearest, nearest), glm::dot(farthest, farthest)};
}

// A point light whose range sphere cuts a region (through its middle, or near its nearest or
// farthest point): its window has a kink there (slope −4/range on one side, 0 on the other),
// which no first-order expansion follows, so it does not fold. With the range a little longer (all
// the region within it) it folds and stays within its bound; a little shorter (none of it), it
// gives nothing.
TEST(FarField, ALightWhoseRangeSphereCutsTheRegionDoesNotFold) {
  const glm::vec3 lo(-0.1f, 0.0f, -0.1f), hi(0.1f, 0.2f, 0.1f);
  const RegionTerms region = regionOf(lo, hi, {0.0f, 1.0f, 0.0f}, 0.0f);
  Light light;
  light.position = {0.3f, 2.1f, -0.2f};
  const double toCentre = glm::length(glm::dvec3(light.position) - glm::dvec3(region.centre));
  const glm::dvec2 d2 = distances2(glm::dvec3(light.position), glm::dvec3(lo), glm::dvec3(hi));
  const glm::dvec3 n(0.0, 1.0, 0.0);
  const struct {
    double range;
    float expected;  // −1: does not fold; kZeroEntry; 0: folds (then T > 0 is checked)
  } cases[] = {{toCentre, -1.0f},
               {std::sqrt(d2.x) * 1.01, -1.0f},
               {std::sqrt(d2.y) * 0.99, -1.0f},
               {std::sqrt(d2.y) * 1.01, 0.0f},
               {std::sqrt(d2.x) * 0.99, kZeroEntry}};
  for (const auto& k : cases) {
    light.range = float(k.range);
    SCOPED_TRACE(k.range);
    FoldLanes in{};
    setEntry(in, light);
    float t[kLanes];
    foldBounds(region, in, 1, t);
    if (k.expected != 0.0f) {
      EXPECT_EQ(t[0], k.expected);
      continue;
    }
    ASSERT_GT(t[0], 0.0f);
    const std::vector<std::uint32_t> words = farFieldOf(light, region.centre);
    for (const glm::dvec3 x : {glm::dvec3(lo), glm::dvec3(hi), glm::dvec3(-0.1, 0.2, 0.1)}) {
      const double exact = unitRadiance(light, x, n).x * shading::kPi;
      const double error = std::abs(farFieldIrradiance(words.data(), x, n).x - exact);
      EXPECT_LE(error, double(t[0]) * shading::kPi + 1e-6 * exact);
    }
  }
  // Folded with its range sphere through the centre, it would be off by far more than the
  // bound its distance and range give inside the range: 6/r⁴ + 2a² (far_field.h).
  light.range = float(toCentre);
  const std::vector<std::uint32_t> words = farFieldOf(light, region.centre);
  const double r2 = d2.x, a = 1.0 / (double(light.range) * double(light.range));
  const double bound = 0.5 * (6.0 / (r2 * r2) + 2.0 * a * a) * double(region.h2);
  // The centre lies on the kink, within float rounding: the far field follows one side of
  // it, so the corner nearest the light or the farthest one is off by the other's slope.
  double error = 0.0;
  for (const glm::dvec3 x : {glm::dvec3(0.1, 0.2, -0.1), glm::dvec3(-0.1, 0.0, 0.1)}) {
    error = std::max(error, std::abs(farFieldIrradiance(words.data(), x, n).x -
                                     unitRadiance(light, x, n).x * shading::kPi));
  }
  EXPECT_GT(error, 2.0 * bound);
}

// Random regions and point or spot lights, many of them near their range: every entry that
// folds has the whole region within its range and stays within its bound T at points and
// normals of the region, against the exact double-precision value; none whose range sphere
// cuts the region folds.
TEST(FarField, FoldedEntriesStayWithinTheirBoundAndInRange) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto unitVector = [&] {
    const glm::dvec3 v(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    return glm::normalize(v + glm::dvec3(0.0, 1e-3, 0.0));
  };
  int folds = 0, rangedFolds = 0, spotFolds = 0, cut = 0;
  double worst = 0.0;  // largest error / (T π)
  for (int round = 0; round < 3000; ++round) {
    const glm::dvec3 centre(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    const glm::dvec3 half = glm::dvec3(0.02 + 0.3 * u(rng)) * glm::dvec3(1.0, u(rng), 1.0);
    const glm::vec3 lo(centre - half), hi(centre + half);
    const glm::dvec3 axis = unitVector();
    const RegionTerms region = regionOf(lo, hi, glm::vec3(axis), rng() % 2 ? 0.0f : 0.3f);
    Light light;
    light.type = rng() % 2 ? LightType::Spot : LightType::Point;
    light.position = glm::vec3(centre + (0.6 + 3.0 * u(rng)) * glm::normalize(axis + unitVector()));
    const glm::dvec3 p(light.position);
    light.direction = glm::vec3(glm::normalize(centre - p + 0.3 * unitVector()));
    light.outerConeAngle = float(0.3 + 0.7 * u(rng));
    light.innerConeAngle = 0.5f * light.outerConeAngle;
    const glm::dvec2 d2 = distances2(p, glm::dvec3(lo), glm::dvec3(hi));
    // No range, or one from a little short of the nearest point to past the farthest.
    light.range =
        rng() % 4 == 0 ? 0.0f : float(std::sqrt(glm::mix(0.9 * d2.x, 1.2 * d2.y, u(rng))));
    FoldLanes in{};
    setEntry(in, light);
    float t[kLanes];
    foldBounds(region, in, 1, t);
    const double range2 = double(light.range) * double(light.range);
    const bool cuts = light.range > 0.0f && d2.x < range2 && d2.y >= range2;
    cut += cuts ? 1 : 0;
    if (t[0] < 0.0f) continue;
    ASSERT_FALSE(cuts) << "round " << round
                       << ": folded a light whose range sphere cuts the region";
    ++folds;
    rangedFolds += light.range > 0.0f ? 1 : 0;
    spotFolds += light.type == LightType::Spot ? 1 : 0;
    const std::vector<std::uint32_t> words = farFieldOf(light, region.centre);
    const double bound = double(t[0]) * shading::kPi;  // per unit irradiance
    for (int sample = 0; sample < 16; ++sample) {
      const glm::dvec3 x =
          glm::mix(glm::dvec3(lo), glm::dvec3(hi), glm::dvec3(u(rng), u(rng), u(rng)));
      glm::dvec3 n = axis;  // a normal within the region's spread of its axis
      const glm::dvec3 m = glm::normalize(axis + 0.3 * unitVector());
      if (glm::dot(m, axis) >= double(region.g.cosSpread)) n = m;
      const double exact = unitRadiance(light, x, n).x * shading::kPi;
      const double error = std::abs(farFieldIrradiance(words.data(), x, n).x - exact);
      // F and J are computed in single precision: 1e-5 of the value at the nearest point.
      const double allowed = bound + 1e-5 / d2.x;
      EXPECT_LE(error, allowed) << "round " << round << " sample " << sample;
      worst = std::max(worst, error / bound);
    }
  }
  EXPECT_GT(folds, 500);
  EXPECT_GT(rangedFolds, 200);
  EXPECT_GT(spotFolds, 200);
  EXPECT_GT(cut, 200);
  EXPECT_LT(worst, 1.0);
  std::printf("folds %d (ranged %d, spots %d), range cuts the region %d, worst error/T %.3f\n",
              folds, rangedFolds, spotFolds, cut, worst);
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
