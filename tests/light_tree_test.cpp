// Light trees (bake/light_tree.h) and their packing: layout, padding, bounds, sums,
// representatives, determinism.
#include "bake/light_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "bake/light_tree_layout.h"
#include "bake/light_tree_pack.h"
#include "bake/tree_update.h"
#include "generators/scene_builder.h"

namespace manylight {
namespace {

std::vector<Light> randomLights(int count, bool mixed, std::uint32_t seed = 5) {
  return scatteredLights(count, mixed, seed, {10.0f, 3.0f, 10.0f});
}

bool inside(glm::vec3 p, const LightTreeNode& n) {
  return glm::all(glm::greaterThanEqual(p, n.boxMin)) && glm::all(glm::lessThanEqual(p, n.boxMax));
}

// Checks every invariant of `tree` against the lights it was built from.
void checkTree(const LightTree& tree, const std::vector<Light>& lights, const LightOrder& order) {
  ASSERT_GE(tree.leafCount, 1);
  ASSERT_EQ(tree.leafCount & (tree.leafCount - 1), 0) << "leaf count is a power of two";
  ASSERT_EQ(tree.nodes.size(), std::size_t(2 * tree.leafCount - 1));
  // Leaves: each light of the type exactly once, the rest empty.
  std::map<int, int> seen;
  for (int i = tree.firstLeaf(); i < int(tree.nodes.size()); ++i) {
    const LightTreeNode& n = tree.nodes[i];
    if (n.empty()) {
      EXPECT_EQ(n.intensity, glm::vec3(0.0f));
      continue;
    }
    ++seen[n.representative];
    const Light& l = lights[order.scene[n.representative]];
    EXPECT_EQ(l.type, tree.type);
    const glm::vec3 point = l.type == LightType::Directional ? -l.direction : l.position;
    EXPECT_EQ(n.boxMin, point);
    EXPECT_EQ(n.boxMax, point);
    EXPECT_EQ(n.intensity, l.colour * l.intensity);
  }
  int ofType = 0;
  for (const Light& l : lights) ofType += l.type == tree.type;
  EXPECT_EQ(int(seen.size()), ofType);
  for (const auto& [slot, count] : seen) EXPECT_EQ(count, 1) << "slot " << slot;
  // Internal nodes: unions and sums of their children; the representative is a child's.
  for (int i = tree.firstLeaf() - 1; i >= 0; --i) {
    const LightTreeNode& n = tree.nodes[i];
    const LightTreeNode& a = tree.nodes[2 * i + 1];
    const LightTreeNode& b = tree.nodes[2 * i + 2];
    EXPECT_EQ(n.empty(), a.empty() && b.empty()) << "node " << i;
    if (n.empty()) continue;
    EXPECT_TRUE(n.representative == a.representative || n.representative == b.representative);
    const glm::vec3 sum =
        (a.empty() ? glm::vec3(0.0f) : a.intensity) + (b.empty() ? glm::vec3(0.0f) : b.intensity);
    EXPECT_NEAR(n.intensity.r, sum.r, 1e-5f * sum.r + 1e-7f);
    for (const LightTreeNode* c : {&a, &b}) {
      if (c->empty()) continue;
      EXPECT_TRUE(inside(c->boxMin, n) && inside(c->boxMax, n)) << "node " << i;
      if (tree.type == LightType::Spot) {
        const double angle = std::acos(std::clamp(
            glm::dot(glm::normalize(glm::dvec3(n.axis)), glm::normalize(glm::dvec3(c->axis))), -1.0,
            1.0));
        EXPECT_LE(angle + c->spread, n.spread + 1e-7) << "cone of node " << i;  // acos rounding
        EXPECT_GE(n.outerAngle, c->outerAngle);
      }
      EXPECT_TRUE(n.invRange2 == 0.0f || (c->invRange2 > 0.0f && n.invRange2 <= c->invRange2));
      EXPECT_GE(n.invRange2Max, c->invRange2Max);
    }
  }
}

TEST(LightTree, EveryCountGivesACompleteTreeHoldingEachLightOnce) {
  for (int count : {1, 2, 3, 4, 5, 7, 64, 1009, 1023, 1024, 1025}) {
    for (bool mixed : {false, true}) {
      const auto lights = randomLights(count, mixed);
      const LightOrder order = lightOrder(lights);
      for (Split split : {Split::Metric, Split::LongestAxis}) {
        TreeOptions options;
        options.split = split;
        const auto trees = buildLightTrees(lights, options);
        ASSERT_EQ(trees.size(), std::size_t(mixed ? std::min(count, 3) : 1)) << count;
        for (const LightTree& t : trees) {
          SCOPED_TRACE("count " + std::to_string(count) + " type " + std::to_string(int(t.type)));
          checkTree(t, lights, order);
        }
      }
    }
  }
}

// Nodes compared field by field (bit for bit).
bool sameNodes(const std::vector<LightTree>& a, const std::vector<LightTree>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t t = 0; t < a.size(); ++t) {
    if (a[t].nodes.size() != b[t].nodes.size()) return false;
    for (std::size_t i = 0; i < a[t].nodes.size(); ++i) {
      const LightTreeNode &x = a[t].nodes[i], &y = b[t].nodes[i];
      if (x.boxMin != y.boxMin || x.boxMax != y.boxMax || x.intensity != y.intensity ||
          x.representative != y.representative || x.invRange2 != y.invRange2 ||
          x.invRange2Max != y.invRange2Max || x.axis != y.axis || x.spread != y.spread ||
          x.outerAngle != y.outerAngle)
        return false;
    }
  }
  return true;
}

TEST(LightTree, RefitsInPlaceAndBackToTheBuild) {
  std::vector<Light> lights = scatteredLights(3000, true, 5, {10.0f, 4.0f, 10.0f});
  const std::vector<LightTree> built = buildLightTrees(lights);
  std::vector<LightTree> trees = built;
  const std::vector<Light> rest = lights;
  std::vector<int> changed;
  for (int i = 0; i < 3000; i += 37) {
    changed.push_back(i);
    lights[std::size_t(i)].position += glm::vec3(0.5f, -0.25f, 1.0f);
    lights[std::size_t(i)].intensity *= 2.0f;
  }
  ASSERT_TRUE(refitLightTrees(trees, lights, changed));
  EXPECT_FALSE(sameNodes(trees, built));
  // Every node's box holds its lights, moved: the root's holds every position.
  for (const LightTree& tree : trees) {
    const LightTreeNode& root = tree.nodes[0];
    for (const Light& l : lights) {
      if (l.type != tree.type || l.type == LightType::Directional) continue;
      EXPECT_TRUE(glm::all(glm::lessThanEqual(root.boxMin, l.position)) &&
                  glm::all(glm::lessThanEqual(l.position, root.boxMax)));
    }
  }
  // Moved back: the trees the build gave, bit for bit.
  ASSERT_TRUE(refitLightTrees(trees, rest, changed));
  EXPECT_TRUE(sameNodes(trees, built));
  // A light that changes type is refused (DynamicTrees keeps the types the trees were built
  // for; refitLightTrees requires them unchanged).
  DynamicTrees dynamic(rest, {});
  EXPECT_TRUE(dynamic.update(lights, changed));
  std::vector<Light> retyped = rest;
  retyped[1].type = retyped[1].type == LightType::Point ? LightType::Spot : LightType::Point;
  EXPECT_FALSE(dynamic.update(retyped, {1}));
}

TEST(LightTree, NoLightsGiveNoTrees) { EXPECT_TRUE(buildLightTrees({}).empty()); }

TEST(LightTree, BuildsAreDeterministic) {
  const auto lights = randomLights(5000, true);
  const auto a = packLightTrees(buildLightTrees(lights));
  const auto b = packLightTrees(buildLightTrees(lights));
  EXPECT_EQ(a.words, b.words);
}

TEST(LightTree, RepresentativeIsChosenInProportionToIntensity) {
  // Two lights, 3:1: over many seeds the brighter one represents the root 3/4 of the time.
  std::vector<Light> lights(2);
  lights[0].position = {0, 0, 0};
  lights[0].intensity = 3.0f;
  lights[1].position = {1, 0, 0};
  lights[1].intensity = 1.0f;
  int brighter = 0;
  const int trials = 4000;
  for (int seed = 0; seed < trials; ++seed) {
    TreeOptions options;
    options.seed = std::uint64_t(seed) * 7919u;
    brighter += buildLightTrees(lights, options)[0].nodes[0].representative == 0;
  }
  EXPECT_NEAR(double(brighter) / trials, 0.75, 0.03);
}

TEST(LightTree, MetricSplitGivesSmallerClustersThanTheLongestAxis) {
  // Over scattered lights, the sum of the paper's cluster metric over all nodes (what the
  // metric split minimises split by split) is no larger than with longest-axis splits.
  const auto lights = randomLights(4096, false, 9);
  double metric = 0.0, longest = 0.0;
  for (Split split : {Split::Metric, Split::LongestAxis}) {
    TreeOptions options;
    options.split = split;
    const LightTree t = buildLightTrees(lights, options)[0];
    double sum = 0.0;
    for (const LightTreeNode& n : t.nodes) sum += clusterMetric(n, 0.0);
    (split == Split::Metric ? metric : longest) = sum;
  }
  EXPECT_LE(metric, longest);
}

TEST(LightTree, PackedWordsFollowTheLayout) {
  const auto lights = randomLights(10, true);
  const auto trees = buildLightTrees(lights);
  const PackedTrees packed = packLightTrees(trees);
  ASSERT_EQ(trees.size(), 3u);
  EXPECT_EQ(packed.words.size() % 4, 0u);
  auto asFloat = [&](std::size_t word) {
    float f;
    std::memcpy(&f, &packed.words[word], sizeof f);
    return f;
  };
  for (const LightTree& t : trees) {
    // Texture order: directional 0, point 1, spot 2.
    const int type = t.type == LightType::Directional ? 0 : t.type == LightType::Point ? 1 : 2;
    const int stride = t.type == LightType::Spot ? layout::kSpotNodeWords : layout::kNodeWords;
    EXPECT_EQ(packed.leaves[type], t.leafCount);
    EXPECT_EQ(packed.base[type] % 2, 0);  // the shader's fetch needs even starts
    for (std::size_t i = 0; i < t.nodes.size(); ++i) {
      const LightTreeNode& n = t.nodes[i];
      const std::size_t w = std::size_t(packed.base[type]) + stride * i;
      EXPECT_EQ(asFloat(w + 0), n.boxMin.x);
      EXPECT_EQ(std::int32_t(packed.words[w + 3]), n.representative);
      EXPECT_EQ(asFloat(w + 7), n.invRange2);
      if (int(i) < t.firstLeaf()) {
        EXPECT_EQ(asFloat(w + 6), n.boxMax.z);
        const glm::vec3 decoded = packed.colour.decode(packed.words[w + 8]);
        const float largest = std::max(n.intensity.r, std::max(n.intensity.g, n.intensity.b));
        for (int c = 0; c < 3; ++c) {
          EXPECT_LE(std::abs(decoded[c] - n.intensity[c]), packed.colour.slack * largest * 1.01f);
        }
      } else {  // leaves: the exact intensity where an internal node has its box maximum
        EXPECT_EQ(n.boxMin, n.boxMax);
        EXPECT_EQ(asFloat(w + 4), n.intensity.r);
        EXPECT_EQ(asFloat(w + 6), n.intensity.b);
        EXPECT_EQ(packed.words[w + 8], 0u);
      }
      if (t.type == LightType::Point) {
        EXPECT_EQ(asFloat(w + 9), n.invRange2Max);
      }
      if (t.type == LightType::Spot && !n.empty()) {
        const double theta = std::acos(double(asFloat(w + 9)));
        EXPECT_GE(theta, std::min(double(n.spread + n.outerAngle), 3.14159) - 1e-6);
        EXPECT_NEAR(asFloat(w + 13), std::sin(theta), 1e-5);
        EXPECT_EQ(asFloat(w + 10), n.axis.x);
      }
    }
  }
}

}  // namespace
}  // namespace manylight
