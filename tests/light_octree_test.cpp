// The light octree (bake/light_octree.h): every light that reaches a point is in that
// point's leaf list, and the lists stay close to the lights that reach.
#include "bake/light_octree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "bake/light_pack.h"
#include "bake/linkless_octree.h"
#include "bake/octree_lights.h"
#include "bake/octree_update.h"
#include "generators/light_layouts.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

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
ListCheck checkLists(const std::vector<Light>& lights, const LightOctree& o, float half, int points,
                     std::uint32_t seed) {
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
      if (!lightReaches(lights[std::size_t(o.order[slot])], p)) continue;
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

namespace manylight {
namespace {

const Scene& room() { return testing::untexturedRoom(); }

// `count` points on the room's triangles, uniformly by area.
std::vector<glm::vec3> surfacePoints(const Scene& scene, int count, std::uint32_t seed) {
  std::vector<std::array<glm::vec3, 3>> triangles;
  std::vector<double> area;
  for (const MeshInstance& inst : scene.instances) {
    for (const Primitive& p : scene.meshes[std::size_t(inst.mesh)].primitives) {
      for (std::size_t i = 0; i + 3 <= p.indices.size(); i += 3) {
        std::array<glm::vec3, 3> t;
        for (int k = 0; k < 3; ++k)
          t[std::size_t(k)] =
              glm::vec3(inst.world * glm::vec4(p.positions[p.indices[i + std::size_t(k)]], 1.0f));
        triangles.push_back(t);
        area.push_back((area.empty() ? 0.0 : area.back()) +
                       glm::length(glm::cross(t[1] - t[0], t[2] - t[0])));
      }
    }
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<glm::vec3> points;
  for (int k = 0; k < count; ++k) {
    const auto it = std::lower_bound(area.begin(), area.end(), u(rng) * area.back());
    const auto& t = triangles[std::size_t(it - area.begin())];
    double a = u(rng), b = u(rng);
    if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
    points.push_back(t[0] + float(a) * (t[1] - t[0]) + float(b) * (t[2] - t[0]));
  }
  return points;
}

// Lights that reach `p` but are in neither its leaf list nor the global list of `o`, and
// lights listed twice.
struct Miss {
  long long missed = 0, doubled = 0, listed = 0, reaching = 0;
};
Miss missesAt(const std::vector<Light>& lights, const LinklessOctree& o,
              const std::vector<glm::vec3>& points) {
  Miss m;
  std::vector<int> listed(lights.size());
  for (const glm::vec3& p : points) {
    std::fill(listed.begin(), listed.end(), 0);
    const OctreeList list = linklessListAt(o, p);
    for (std::uint32_t i = 0; i < o.globalCount; ++i) ++listed[o.indices[i]];
    for (std::uint32_t i = 0; i < list.count; ++i) ++listed[o.indices[list.first + i]];
    for (std::size_t slot = 0; slot < lights.size(); ++slot) {
      m.doubled += listed[slot] > 1;
      m.listed += listed[slot];
      if (!lightReaches(lights[std::size_t(o.order[slot])], p)) continue;
      ++m.reaching;
      m.missed += listed[slot] == 0;
    }
  }
  return m;
}

TEST(LinklessOctree, FindsTheLeafTheOctreeHoldsAtEveryPoint) {
  const std::vector<Light> lights = layoutLights(LightLayout::UniformRanged, 4096, 7);
  const LightOctree octree = buildLightOctree(lights, room());
  const LinklessOctree packed = packLinklessOctree(octree);
  for (const LinklessLevel& l : packed.level) {
    EXPECT_LE(double(l.dims.x) * l.dims.y * l.dims.z, 1.1 * std::max(l.nodeCount, 1));
  }
  const std::vector<glm::vec3> points = surfacePoints(room(), 20000, 3);
  for (const glm::vec3& p : points) {
    const OctreeList a = octreeListAt(octree, p), b = linklessListAt(packed, p);
    ASSERT_EQ(a.count, b.count);
    if (a.count) {
      ASSERT_EQ(b.first, a.first + packed.globalCount);
    }
  }
  const Miss m = missesAt(lights, packed, points);
  EXPECT_EQ(m.missed, 0);
  EXPECT_EQ(m.doubled, 0);
  EXPECT_GT(m.reaching, 20 * 20000);
}

TEST(DynamicOctree, MovedLightsAreListedWhereTheyReachAndNowhereTwice) {
  std::vector<Light> lights = layoutLights(LightLayout::UniformRanged, 4096, 7);
  DynamicOctree dynamic(lights, room());
  const std::vector<glm::vec3> points = surfacePoints(room(), 5000, 4);
  std::mt19937 rng(9);
  std::uniform_int_distribution<int> pick(0, int(lights.size()) - 1);
  std::uniform_real_distribution<float> step(-0.6f, 0.6f);
  for (int frame = 0; frame < 5; ++frame) {
    std::vector<int> changed;
    for (int k = 0; k < 200; ++k) changed.push_back(pick(rng));
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    for (int i : changed)
      lights[std::size_t(i)].position += glm::vec3(step(rng), step(rng), step(rng));
    ASSERT_TRUE(dynamic.update(lights, changed));
    const Miss m = missesAt(lights, dynamic.packed(), points);
    EXPECT_EQ(m.missed, 0) << "frame " << frame;
    EXPECT_EQ(m.doubled, 0) << "frame " << frame;
  }
  // A light that loses its range cannot stay in the octree.
  lights[0].range = 0.0f;
  EXPECT_FALSE(dynamic.update(lights, {0}));
}

// The order, the classification and the sorting of lists into children run on several
// threads from 32,768 lights on: the octree does not depend on how many.
TEST(LightOctree, IsTheSameOnAnyNumberOfThreads) {
  std::vector<Light> lights = layoutLights(LightLayout::StreetRanged, 40000, 5);
  lights[17].range = 0.0f;  // one for the global list
  OctreeOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const LightOctree a = buildLightOctree(lights, room(), one);
  const LightOctree b = buildLightOctree(lights, room(), three);
  EXPECT_EQ(a.order, b.order);
  EXPECT_EQ(a.global, b.global);
  ASSERT_EQ(a.global.size(), 1u);
  EXPECT_EQ(a.order[a.global[0]], 17);
  EXPECT_EQ(a.indices, b.indices);
  ASSERT_EQ(a.levels, b.levels);
  for (int level = 0; level < a.levels; ++level) {
    ASSERT_EQ(a.nodes[level].size(), b.nodes[level].size());
    for (std::size_t k = 0; k < a.nodes[level].size(); ++k) {
      EXPECT_EQ(a.nodes[level][k].childMask, b.nodes[level][k].childMask);
      EXPECT_EQ(a.nodes[level][k].first, b.nodes[level][k].first);
      EXPECT_EQ(a.nodes[level][k].count, b.nodes[level][k].count);
    }
  }
}

// A leaf edge whose lists would plainly exceed the budget is passed over for a coarser one
// (their entries are estimated before a build); what is built still lists every light
// where it reaches.
TEST(LightOctree, ALeafEdgeTooFineForTheBudgetGivesWayToACoarserOne) {
  const std::vector<Light> lights = layoutLights(LightLayout::StreetRanged, 4096, 7);
  OctreeOptions fine;
  fine.leafEdge = 0.05f * octreeLeafEdge(lights);
  const LightOctree o = buildLightOctree(lights, room(), fine);
  EXPECT_GE(o.leafEdge, 4.0f * fine.leafEdge);
  EXPECT_LE(o.indices.size(), kMinOctreeBudget);
  EXPECT_GT(o.indices.size(), kMinOctreeBudget / 8);
  const Miss m = missesAt(lights, packLinklessOctree(o), surfacePoints(room(), 5000, 8));
  EXPECT_EQ(m.missed, 0);
  EXPECT_EQ(m.doubled, 0);
}

// Where every cell a light meets is split to the deepest level, the estimate from a
// thousand lights is close to the entries the build writes.
TEST(LightOctree, EstimatesItsListEntriesBeforeBuilding) {
  for (LightLayout layout : {LightLayout::StreetRanged, LightLayout::UniformRanged}) {
    const std::vector<Light> lights = layoutLights(layout, 20000, 3);
    const LightOctree built = buildLightOctree(lights, room());
    LightOctree o;
    o.order = built.order;
    const octree::Classified c = octree::classify(lights, room().bounds(), false, 1, o);
    o.origin = built.origin, o.leafEdge = built.leafEdge, o.levels = built.levels;
    o.margin = c.margin;
    const SurfaceCells surfaces = surfaceCells(room(), o.origin, o.leafEdge, o.levels, o.margin);
    const double estimate = octree::estimatedEntries(o, surfaces, c);
    EXPECT_NEAR(estimate / double(built.indices.size()), 1.0, 0.1) << int(layout);
  }
}

}  // namespace
}  // namespace manylight
