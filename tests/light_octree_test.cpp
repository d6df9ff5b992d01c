// The light octree (bake/light_octree.h): every light that reaches a point is in that
// point's leaf list, and the lists stay close to the lights that reach.
#include "bake/light_octree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "bake/light_pack.h"

namespace manylight {
namespace {

// `count` ranged lights in the box [−5, 5]³: points, and every third a spot in a random
// direction with a random cone.
std::vector<Light> randomLights(int count, float range, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f), unit(-1.0f, 1.0f), angle(0.05f, 1.5f);
  std::vector<Light> lights(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    Light& l = lights[std::size_t(i)];
    l.position = {u(rng), u(rng), u(rng)};
    l.range = range * (0.5f + 0.25f * (unit(rng) + 1.0f));
    if (i % 3 == 2) {
      l.type = LightType::Spot;
      l.direction = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) + glm::vec3(1e-3f));
      l.outerConeAngle = std::min(angle(rng), 1.5707963f);
      l.innerConeAngle = 0.5f * l.outerConeAngle;
    }
  }
  return lights;
}

// A scene without geometry: the octree is refined everywhere.
Scene noGeometry() { return Scene{}; }

struct ListCheck {
  long long missed = 0, listed = 0, reaching = 0;
};

// At `points` random points of [−half, half]³: lights that reach but are not listed, and the
// list lengths against the lights reaching.
ListCheck checkLists(const std::vector<Light>& lights, const LightOctree& o, float half,
                     int points, std::uint32_t seed) {
  const LightOrder order = lightOrder(lights);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-half, half);
  ListCheck check;
  std::vector<char> listed(lights.size());
  for (int k = 0; k < points; ++k) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    std::fill(listed.begin(), listed.end(), 0);
    const OctreeList list = octreeListAt(o, p);
    for (std::uint32_t i = 0; i < list.count; ++i) listed[o.indices[list.first + i]] = 1;
    for (std::uint32_t slot : o.global) listed[slot] = 1;
    check.listed += list.count + o.global.size();
    for (std::size_t slot = 0; slot < lights.size(); ++slot) {
      if (!lightReaches(lights[std::size_t(order.scene[slot])], p)) continue;
      ++check.reaching;
      if (!listed[slot]) ++check.missed;
    }
  }
  return check;
}

TEST(LightOctree, ListsHoldEveryLightThatReaches) {
  const std::vector<Light> lights = randomLights(3000, 1.0f, 7);
  const LightOctree o = buildLightOctree(lights, noGeometry());
  const ListCheck check = checkLists(lights, o, 6.0f, 20000, 11);
  EXPECT_EQ(check.missed, 0);
  EXPECT_GT(check.reaching, 20000);
  EXPECT_LT(double(check.listed), 2.0 * double(check.reaching));
  EXPECT_TRUE(o.global.empty());
  std::printf("levels %d leaf %.3f nodes %zu indices %zu listed/reaching %.3f\n", o.levels,
              o.leafEdge, o.nodeCount(), o.indices.size(),
              double(check.listed) / double(check.reaching));
}

}  // namespace
}  // namespace manylight
