// The walk of a scene with many roots (scene/scene_walker.h), which goes in shares on
// several threads: the same Scene as one walk in order, and the error of the first faulty
// node in walk order whichever share meets it.
#include "scene/scene_walker.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "base/error.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

constexpr int kNodes = int(gltf::SceneWalker::kParallelRoots) + 4464;  // 70,000

// Extra JSON properties of some nodes, by index.
using Extras = std::map<int, std::string>;

// kNodes light nodes, each placed differently: camera 0 on node 60,000, camera 1 on nodes
// 69,000 and 20 (in different shares: the first in walk order, node 20, places it). `grouped`:
// under one parent node (the last, at the origin), so one walk goes through them; else each is a
// scene root.
std::string manyLights(bool grouped, const Extras& extras = {}, const std::string& more = "") {
  std::string nodes;
  for (int i = 0; i < kNodes; ++i) {
    nodes += "{\"translation\": [" + std::to_string(i % 97) + ", " + std::to_string(i % 13) +
             ".25, -" + std::to_string(i / 1000) + "], \"rotation\": [0, 0.6, 0, 0.8]";
    if (i == 60000 || i == 69000 || i == 20)
      nodes += ", \"camera\": " + std::to_string(i == 60000 ? 0 : 1);
    if (extras.count(i)) nodes += ", " + extras.at(i);
    nodes +=
        ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": " + std::to_string(i % 3) + "}}},";
  }
  std::string roots;
  if (grouped) {
    nodes += "{\"children\": [";
    for (int i = 0; i < kNodes; ++i) nodes += std::to_string(i) + (i + 1 < kNodes ? "," : "");
    nodes += "]}";
    roots = std::to_string(kNodes);
  } else {
    nodes.pop_back();
    for (int i = 0; i < kNodes; ++i) roots += std::to_string(i) + (i + 1 < kNodes ? "," : "");
  }
  return R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25]},
    {"type": "spot", "intensity": 3, "range": 7, "spot": {"outerConeAngle": 0.5}},
    {"type": "directional", "intensity": 0.5}]}},
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}},
    {"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1}}],
  "nodes": [)" +
         nodes + "], \"scenes\": [{\"nodes\": [" + roots + more + "]}]}";
}

TEST(SceneWalker, ManyRootsGiveTheSceneOfOneWalkInOrder) {
  const Scene shared = loadGltf(writeFile("roots.gltf", manyLights(false)));
  const Scene one = loadGltf(writeFile("grouped.gltf", manyLights(true)));
  ASSERT_EQ(shared.lights.size(), std::size_t(kNodes));
  ASSERT_EQ(one.lights.size(), std::size_t(kNodes));
  for (int i = 0; i < kNodes; ++i) {
    const Light &a = shared.lights[std::size_t(i)], &b = one.lights[std::size_t(i)];
    ASSERT_EQ(a.type, b.type) << "light " << i;
    ASSERT_EQ(a.position, b.position) << "light " << i;
    ASSERT_EQ(a.direction, b.direction) << "light " << i;
    ASSERT_EQ(a.colour, b.colour) << "light " << i;
    ASSERT_EQ(a.intensity, b.intensity) << "light " << i;
    ASSERT_EQ(a.range, b.range) << "light " << i;
  }
  EXPECT_EQ(shared.lights[1].type, LightType::Spot);
  EXPECT_EQ(shared.lights[69999].position, glm::vec3(69999 % 97, 69999 % 13 + 0.25f, -69.0f));
  ASSERT_EQ(shared.cameras.size(), 2u);
  for (int c = 0; c < 2; ++c)
    EXPECT_EQ(shared.cameras[std::size_t(c)].world, one.cameras[std::size_t(c)].world);
  // Camera 1 is placed by node 20, camera 0 by node 60,000.
  EXPECT_EQ(glm::vec3(shared.cameras[1].world[3]), glm::vec3(20, 7.25f, 0));
  EXPECT_EQ(glm::vec3(shared.cameras[0].world[3]), glm::vec3(60000 % 97, 60000 % 13 + 0.25f, -60));
}

TEST(SceneWalker, LightsPastTheBudgetAreCountedAsOneWalkCountsThem) {
  // One walk converts the first 40,000 lights only, counts the rest and then refuses the
  // scene; a light past the budget whose node collapses its direction is never converted.
  LoadOptions options;
  options.lightBudget = 40000;
  const Extras collapsed = {{50000, "\"scale\": [1, 1, 0]"}};
  const std::string path = writeFile("budget.gltf", manyLights(false, collapsed));
  EXPECT_EQ(loadError(path, options),
            path + ": 70000 lights exceed the light budget of 40000 (--light-budget)");
}

TEST(SceneWalker, TheFirstFaultyNodeInWalkOrderIsNamed) {
  // One fault late (in the last share), one early (in the first).
  const Extras late = {{69000, "\"mesh\": -3"}};
  EXPECT_EQ(loadError(writeFile("late.gltf", manyLights(false, late))),
            testFolder().string() + "/late.gltf: node 69000: mesh -3 does not exist");
  const Extras both = {{69000, "\"mesh\": -3"}, {7, "\"scale\": [1e39, 1, 1]"}};
  EXPECT_EQ(loadError(writeFile("both.gltf", manyLights(false, both))),
            testFolder().string() + "/both.gltf: node 7: transform is not finite");
  // A root listed twice: one walk, which meets it again at the end.
  EXPECT_EQ(
      loadError(writeFile("twice.gltf", manyLights(false, {}, ", 5"))),
      testFolder().string() +
          "/twice.gltf: node 5 is reached twice (a scene root listed twice, or also a child)");
}

}  // namespace
}  // namespace manylight::testing
