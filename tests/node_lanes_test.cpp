// The CPU cut's node and fold bounds eight lanes at once (AVX2) against one lane at a time:
// the same results bit for bit, on random nodes and regions that take every branch.
#include "cuts/node_lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace manylight {
namespace {

NodeLanes randomNodes(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  NodeLanes n{};
  for (int l = 0; l < kLanes; ++l) {
    const int tree = int(rng() % 3);
    n.tree[l] = float(tree);
    n.leaf[l] = rng() % 4 == 0 ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c) {
      const float a = 4.0f * u(rng), b = 4.0f * u(rng);
      n.boxMin[c][l] = std::min(a, b);
      n.boxMax[c][l] = n.leaf[l] != 0.0f ? n.boxMin[c][l] : std::max(a, b);
      n.intensity[c][l] = 2.0f + u(rng);
      n.axis[c][l] = u(rng);
      n.repPoint[c][l] = n.boxMin[c][l];
      n.repAxis[c][l] = u(rng);
    }
    switch (rng() % 8) {
      case 0:  // unbounded: infinite intensity
        n.intensity[1][l] = std::numeric_limits<float>::infinity();
        break;
      case 1:  // a box around the region's centre
        for (int c = 0; c < 3; ++c) n.boxMin[c][l] = -5.0f, n.boxMax[c][l] = 5.0f;
        break;
      default:
        break;
    }
    n.invRange2[l] = rng() % 2 ? 0.0f : 0.05f + 0.1f * std::abs(u(rng));
    // Spots: cos θ of their cone; others: the largest 1/range² (lower bounds use it).
    n.w2[l] = tree == 2 ? u(rng) : n.invRange2[l] * 1.5f;
    n.sinTheta[l] = std::sqrt(std::max(1.0f - n.w2[l] * n.w2[l], 0.0f));
    n.repInvRange2[l] = n.invRange2[l];
    n.repCos[l] = u(rng);
    // Spots' cones: the widest's outer cosine in [−0.5, 0.5], its inner above it; the
    // narrowest's cosines at or above them.
    const float outer = 0.5f * u(rng), inner = outer + 0.01f + 0.4f * std::abs(u(rng));
    const float narrowOuter = outer + 0.1f * std::abs(u(rng));
    const float narrowInner = std::max(inner, narrowOuter + 0.01f) + 0.1f * std::abs(u(rng));
    n.spreadCos[l] = u(rng);
    n.upScale[l] = 1.0f / (inner - outer);
    n.upOffset[l] = -outer * n.upScale[l];
    n.lowScale[l] = 1.0f / (narrowInner - narrowOuter);
    n.lowOffset[l] = -narrowOuter * n.lowScale[l];
    n.lowInvRange2[l] = n.invRange2[l] + (rng() % 2 ? 0.1f : 0.0f);
    n.repConeScale[l] = n.upScale[l];
    n.repConeOffset[l] = n.upOffset[l];
    n.knownUnit[l] = rng() % 3 == 0 ? 1.0f : 0.0f;
    n.unit[l] = std::abs(u(rng));
  }
  return n;
}

RegionTerms randomRegion(std::mt19937& rng, bool total) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  RegionTerms r{};
  const glm::vec3 p(u(rng), u(rng), u(rng)), size(0.3f * std::abs(u(rng)));
  r.g.pMin = p - size;
  r.g.pMax = p + size;
  r.g.axis = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.01f, 0.0f));
  r.g.cosSpread = rng() % 5 == 0 ? -0.2f : 0.8f + 0.2f * std::abs(u(rng));
  r.g.sinSpread = std::sqrt(std::max(1.0f - r.g.cosSpread * r.g.cosSpread, 0.0f));
  r.centre = 0.5f * (r.g.pMin + r.g.pMax);
  r.halfDiagonal = 0.5f * glm::length(r.g.pMax - r.g.pMin);
  r.h2 = 0.25f * glm::dot(r.g.pMax - r.g.pMin, r.g.pMax - r.g.pMin);
  r.slackRate = 0.01f;
  r.slackFloor = 1e-6f;
  r.total = total;
  if (rng() % 2 == 0) {  // specular lobes, about a cone of mirror directions
    SpecularLobes& lobes = r.g.lobes;
    lobes.on = true;
    lobes.axis = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.01f, 0.0f, 0.0f));
    lobes.cosSpread = rng() % 5 == 0 ? -1.0f : 0.9f + 0.1f * std::abs(u(rng));
    lobes.sinSpread = std::sqrt(std::max(1.0f - lobes.cosSpread * lobes.cosSpread, 0.0f));
    lobes.minExponent = 1.0f + 10.0f * std::abs(u(rng));
    lobes.maxExponent = lobes.minExponent * (1.0f + 100.0f * std::abs(u(rng)));
    lobes.meanExponent = 0.5f * (lobes.minExponent + lobes.maxExponent);
    r.mirror = ShadingRegion{r.g.pMin,        r.g.pMax,        lobes.axis,
                             lobes.cosSpread, lobes.sinSpread, SpecularLobes{}};
  }
  return r;
}

// The eight-lane path runs where the build has it (MANYLIGHT_AVX2_LANES) and the CPU has
// AVX2 (wideNodeBounds, the library's dispatch); elsewhere both calls below would run one lane
// at a time and compare it with itself.
#define SKIP_WITHOUT_EIGHT_LANES()                                                          \
  if (!wideNodeBounds()) {                                                                  \
    GTEST_SKIP() << "no AVX2 eight-lane path on this machine or build: nothing to compare"; \
  }

TEST(NodeLanes, EightLanesGiveOneLanesResultsBitForBit) {
  SKIP_WITHOUT_EIGHT_LANES();
  std::mt19937 rng(7);
  int unbounded = 0, dark = 0, leaves = 0, bounded = 0, lobeTops = 0, lobeBottoms = 0, walks = 0;
  for (int round = 0; round < 5000; ++round) {
    const NodeLanes in = randomNodes(rng);
    RegionTerms region = randomRegion(rng, round % 2 == 1);
    region.walkBounds = round % 8 >= 6;  // a walk's bounds (CutRule::walkBounds)
    BoundLanes wide, one;
    std::memset(&wide, 0, sizeof wide);
    std::memset(&one, 0, sizeof one);
    nodeBounds(region, in, kLanes, wide, true);
    nodeBounds(region, in, kLanes, one, false);
    ASSERT_EQ(std::memcmp(&wide, &one, sizeof wide), 0) << "round " << round;
    for (int l = 0; l < kLanes; ++l) {
      const float m = one.measure[l];
      if (in.leaf[l] != 0.0f) {
        ++leaves;
        EXPECT_EQ(m, -1.0f);
        EXPECT_EQ(one.error[0][l] + one.error[1][l] + one.error[2][l], 0.0f);
      } else if (std::isinf(m)) {
        ++unbounded;
        EXPECT_EQ(one.dark[l], 0.0f);
      } else {
        EXPECT_GE(m, 0.0f);
        if (one.dark[l] != 0.0f) {
          ++dark;
          EXPECT_EQ(m, 0.0f);
        }
        if (m > 0.0f) ++bounded;
      }
      if (in.knownUnit[l] != 0.0f) {
        EXPECT_EQ(one.unit[l], in.unit[l]);
      }
      if (region.walkBounds) {
        ++walks;
        EXPECT_EQ(one.lobeBottom[l], 0.0f);
      } else if (region.g.lobes.on) {
        lobeTops += one.lobeTop[l] > 0.0f && one.lobeTop[l] < 1.0f ? 1 : 0;
        lobeBottoms += one.lobeBottom[l] > 0.0f && one.lobeBottom[l] < 1.0f ? 1 : 0;
      }
    }
  }
  // Every branch was taken.
  EXPECT_GT(unbounded, 100);
  EXPECT_GT(dark, 100);
  EXPECT_GT(leaves, 100);
  EXPECT_GT(bounded, 100);
  EXPECT_GT(lobeTops, 100);    // the lobes' powers, in [0, 1] (cuts/lane_powers.h)
  EXPECT_GT(lobeBottoms, 20);  // rarer: every cosine of the node must be positive
  EXPECT_GT(walks, 1000);
}

// Nodes gathered into lanes by a transpose and one float at a time; lanes past the count
// take lane 0's node.
TEST(NodeLanes, GatheringByTransposeGivesTheSameLanes) {
  SKIP_WITHOUT_EIGHT_LANES();
  struct alignas(32) Record {
    float f[32];
  };
  std::vector<Record> records(kLanes);
  for (int l = 0; l < kLanes; ++l) {
    for (int k = 0; k < 32; ++k) records[std::size_t(l)].f[k] = float(100 * l + k);
  }
  const float* nodes[kLanes];
  for (int l = 0; l < kLanes; ++l) nodes[l] = records[std::size_t(l)].f;
  for (const int count : {kLanes, 5, 1}) {
    NodeLanes wide{}, one{};
    gatherNodes(nodes, count, wide, true);
    gatherNodes(nodes, count, one, false);
    EXPECT_EQ(std::memcmp(&wide, &one, sizeof wide), 0) << count;
    for (int l = 0; l < kLanes; ++l) {
      const int from = l < count ? l : 0;
      EXPECT_EQ(one.boxMin[0][l], float(100 * from)) << count << " " << l;
      EXPECT_EQ(one.repPoint[2][l], float(100 * from + 17)) << count << " " << l;
      EXPECT_EQ(one.leaf[l], float(100 * from + 23)) << count << " " << l;
    }
  }
}

// Far field terms of point and spot entries, eight at once and one at a time; lanes past the
// count add nothing.
TEST(NodeLanes, EightLanesGiveOneLanesFarFieldSumsBitForBit) {
  SKIP_WITHOUT_EIGHT_LANES();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int round = 0; round < 2000; ++round) {
    FarLanes in{};
    for (int l = 0; l < kLanes; ++l) {
      for (int c = 0; c < 3; ++c) {
        in.position[c][l] = 3.0f * u(rng);
        in.coneAxis[c][l] = u(rng);
        in.intensity[c][l] = 1.0f + u(rng);
      }
      in.invRange2[l] = rng() % 2 ? 0.0f : 0.1f;
      in.spot[l] = rng() % 2 ? 1.0f : 0.0f;
      in.coneScale[l] = 4.0f * std::abs(u(rng));
      in.coneOffset[l] = u(rng);
    }
    const glm::vec3 centre(u(rng), u(rng), u(rng));
    const int count = 1 + round % kLanes;
    FarSums wide{}, one{};
    addFarField(centre, in, count, wide, true);
    addFarField(centre, in, count, one, false);
    ASSERT_EQ(std::memcmp(&wide, &one, sizeof wide), 0) << "round " << round;
    for (int l = count; l < kLanes; ++l) EXPECT_EQ(one.f[0][0][l], 0.0f);
    for (int l = 0; l < count; ++l) {  // a point light with no range adds I v/|v|³
      if (in.spot[l] == 0.0f && in.invRange2[l] == 0.0f) {
        const glm::vec3 v =
            glm::vec3(in.position[0][l], in.position[1][l], in.position[2][l]) - centre;
        const float expected = in.intensity[1][l] * v.y / std::pow(glm::length(v), 3.0f);
        // Both in single precision, by different steps (γ v against I v.y/|v|³): 1e-5 of it.
        EXPECT_NEAR(one.f[1][1][l], expected, 1e-5f * std::abs(expected)) << round << " " << l;
      }
    }
  }
}

// Checks lane l of `in`, which foldBounds called kZeroEntry or kFullCone, at points and
// normals of the region: its light gives nothing (max(n·v, 0) · window · cone is 0), or its
// spot cone is 1.
void checkShape(const RegionTerms& r, const FoldLanes& in, int l, float shape, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec3 rep(in.repPoint[0][l], in.repPoint[1][l], in.repPoint[2][l]);
  const glm::dvec3 axis(in.repAxis[0][l], in.repAxis[1][l], in.repAxis[2][l]);
  const glm::dvec3 mean(r.g.axis);
  for (int sample = 0; sample < 64; ++sample) {
    const glm::dvec3 p =
        glm::mix(glm::dvec3(r.g.pMin), glm::dvec3(r.g.pMax), glm::dvec3(u(rng), u(rng), u(rng)));
    glm::dvec3 n = mean;  // a normal within the region's spread of its axis
    for (int tries = 0; tries < 100; ++tries) {
      const glm::dvec3 m =
          glm::normalize(mean + 2.0 * glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
      if (glm::dot(m, mean) >= double(r.g.cosSpread)) {
        n = m;
        break;
      }
    }
    double value;
    if (in.tree[l] == 0.0f) {
      value = std::max(glm::dot(n, rep), 0.0);
    } else {
      const glm::dvec3 v = rep - p;
      const double d2 = glm::dot(v, v), x = d2 * in.repInvRange2[l];
      const double window = std::clamp(1.0 - x * x, 0.0, 1.0);
      double cone = 1.0;
      if (in.tree[l] == 2.0f) {
        const double t = std::clamp(
            glm::dot(-v / std::sqrt(d2), axis) * in.coneScale[l] + in.coneOffset[l], 0.0, 1.0);
        cone = t * t * (3.0 - 2.0 * t);
        if (shape == kFullCone) {
          EXPECT_EQ(cone, 1.0);
          continue;
        }
      }
      value = std::max(glm::dot(n, v), 0.0) * window * cone;
    }
    ASSERT_EQ(value, 0.0) << "tree " << in.tree[l] << " sample " << sample;
  }
}

// The far field's linearisation bounds of entries, eight at once and one at a time; the
// entries it calls kZeroEntry give nothing anywhere in the region, and kFullCone spots have
// their cone at 1 there.
TEST(NodeLanes, EightLanesGiveOneLanesFoldBoundsBitForBit) {
  SKIP_WITHOUT_EIGHT_LANES();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int folds = 0, unfolded = 0, spotsFolded = 0, zeros = 0, fullCones = 0;
  for (int round = 0; round < 4000; ++round) {
    const RegionTerms region = randomRegion(rng, false);
    FoldLanes in{};
    for (int l = 0; l < kLanes; ++l) {
      in.tree[l] = float(rng() % 3);
      for (int c = 0; c < 3; ++c) {
        in.repPoint[c][l] = 3.0f * u(rng);
        in.repAxis[c][l] = u(rng);
      }
      const glm::vec3 axis =
          glm::normalize(glm::vec3(in.repAxis[0][l], in.repAxis[1][l], in.repAxis[2][l]) +
                         glm::vec3(0.0f, 0.01f, 0.0f));
      for (int c = 0; c < 3; ++c) in.repAxis[c][l] = axis[c];
      if (in.tree[l] == 0.0f) {  // a directional light: the unit vector towards it
        const glm::vec3 d =
            glm::normalize(glm::vec3(in.repPoint[0][l], in.repPoint[1][l], in.repPoint[2][l]));
        for (int c = 0; c < 3; ++c) in.repPoint[c][l] = d[c];
      }
      in.repInvRange2[l] = rng() % 2 ? 0.0f : 0.05f;
      in.repCos[l] = std::abs(u(rng));
      in.coneScale[l] =
          rng() % 10 == 0 ? std::numeric_limits<float>::infinity() : 5.0f * std::abs(u(rng));
      in.coneOffset[l] = u(rng);
    }
    float wide[kLanes], one[kLanes];
    foldBounds(region, in, kLanes, wide, true);
    foldBounds(region, in, kLanes, one, false);
    ASSERT_EQ(std::memcmp(wide, one, sizeof wide), 0) << "round " << round;
    for (int l = 0; l < kLanes; ++l) {
      if (one[l] == kZeroEntry || one[l] == kFullCone) {
        // Sampled over the region's points and normals: nothing, or the cone at 1.
        ++(one[l] == kZeroEntry ? zeros : fullCones);
        checkShape(region, in, l, one[l], rng);
        continue;
      }
      if (one[l] < 0.0f) {
        EXPECT_EQ(one[l], -1.0f);
        ++unfolded;
        continue;
      }
      ++folds;
      if (in.tree[l] == 2.0f) {
        ++spotsFolded;
        EXPECT_TRUE(std::isfinite(in.coneScale[l]));  // a hard edge never folds
      }
      if (in.tree[l] == 0.0f) {
        EXPECT_EQ(one[l], 0.0f);  // a directional light is linear
      }
    }
  }
  EXPECT_GT(folds, 1000);
  EXPECT_GT(unfolded, 1000);
  EXPECT_GT(spotsFolded, 100);
  EXPECT_GT(zeros, 100);
  EXPECT_GT(fullCones, 100);
}

// The lobe's powers (BoundLanes::lobeTop, lobeBottom, lobeTowards) against std::pow in
// double: the upper bound at or above it, the lower at or below, both within 2e-6 + 4e-7 ·
// (e + |e · log₂ x|) of it relatively, the estimate within half that; the eight lanes and
// the one give the same bits.
TEST(NodeLanes, LobePowersBoundThePower) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float exponents[] = {1.0f, 1.5f, 7.8f, 64.0f, 1000.0f, 8192.0f};
  int checked = 0;
  for (int round = 0; round < 20000; ++round) {
    float x[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const float u = unit(rng);
      // Near 1 (where lobes peak), spread over [0, 1], tiny, and the ends exactly.
      x[l] = l == 0 ? 1.0f - u * 1e-3f : l == 1 ? u : l == 2 ? std::pow(u, 40.0f) : u * u;
    }
    if (round == 0) x[3] = 0.0f, x[4] = 1.0f, x[5] = 1e-39f;
    const float e = exponents[round % 6];
    float up[kLanes], low[kLanes], est[kLanes], up1[kLanes], low1[kLanes], est1[kLanes];
    lobePowers(x, e, up, low, est, true);
    lobePowers(x, e, up1, low1, est1, false);
    ASSERT_EQ(std::memcmp(up, up1, sizeof up), 0);
    ASSERT_EQ(std::memcmp(low, low1, sizeof low), 0);
    ASSERT_EQ(std::memcmp(est, est1, sizeof est), 0);
    for (int l = 0; l < kLanes; ++l) {
      const double exact = std::pow(double(x[l]), double(e));
      ASSERT_GE(double(up[l]), exact) << x[l] << "^" << e;
      ASSERT_LE(double(low[l]), exact) << x[l] << "^" << e;
      if (exact < 1e-37) continue;  // below the normal floats: the bounds only
      const double y = std::abs(double(e) * std::log2(double(x[l])));
      const double slack = 2e-6 + 4e-7 * (double(e) + y);
      ASSERT_LE(double(up[l]), exact * (1.0 + slack)) << x[l] << "^" << e;
      ASSERT_GE(double(low[l]), exact * (1.0 - slack)) << x[l] << "^" << e;
      ASSERT_NEAR(double(est[l]), exact, exact * slack / 2.0) << x[l] << "^" << e;
      ++checked;
    }
  }
  EXPECT_GT(checked, 90000);
}

}  // namespace
}  // namespace manylight
