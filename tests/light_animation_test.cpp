// Light animations (scene/light_animation.h): node tracks and KHR_animation_pointer channels
// read from glTF, evaluated at any time, the lights that change listed, bad input refused.
#include "scene/light_animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "base/error.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight {
namespace {

namespace fs = std::filesystem;
using testing::writeFile;

struct Accessor {
  std::vector<float> data;
  const char* type;  // "SCALAR", "VEC3" or "VEC4"
};

// Writes NAME.gltf and NAME.bin: `accessors` one after another in the buffer, then the JSON
// members `rest` (nodes, scenes, animations, extensions). Returns the .gltf's path.
std::string lightScene(const std::string& name, const std::vector<Accessor>& accessors,
                       const std::string& rest) {
  std::string bin, views, list;
  for (std::size_t i = 0; i < accessors.size(); ++i) {
    const std::vector<float>& d = accessors[i].data;
    const int n = std::strcmp(accessors[i].type, "SCALAR") == 0 ? 1
                  : std::strcmp(accessors[i].type, "VEC3") == 0 ? 3
                                                                : 4;
    const std::string sep = i == 0 ? "" : ",";
    views += sep + R"({"buffer": 0, "byteOffset": )" + std::to_string(bin.size()) +
             R"(, "byteLength": )" + std::to_string(d.size() * 4) + "}";
    list += sep + R"({"bufferView": )" + std::to_string(i) +
            R"(, "componentType": 5126, "count": )" + std::to_string(d.size() / n) +
            R"(, "type": ")" + accessors[i].type + "\"}";
    bin.append(reinterpret_cast<const char*>(d.data()), d.size() * 4);
  }
  writeFile(name + ".bin", bin);
  return writeFile(name + ".gltf", R"({"asset": {"version": "2.0"},
      "extensionsUsed": ["KHR_lights_punctual", "KHR_animation_pointer"], "buffers": [{"uri": ")" +
                                       name + ".bin\", \"byteLength\": " +
                                       std::to_string(bin.size()) + "}], \"bufferViews\": [" +
                                       views + "], \"accessors\": [" + list + "], " + rest + "}");
}

// KHR_lights_punctual's lights, as JSON.
std::string lights(const std::string& list) {
  return R"("extensions": {"KHR_lights_punctual": {"lights": [)" + list + "]}}";
}
std::string channel(int sampler, const std::string& target) {
  return R"({"sampler": )" + std::to_string(sampler) + R"(, "target": )" + target + "}";
}
std::string pointer(const std::string& p) {
  return R"({"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": ")" + p +
         "\"}}}";
}
std::string sampler(int input, int output, const char* interpolation = "LINEAR") {
  return R"({"input": )" + std::to_string(input) + R"(, "output": )" + std::to_string(output) +
         R"(, "interpolation": ")" + interpolation + "\"}";
}

void expectSame(const Light& a, const Light& b) {
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_EQ(a.colour, b.colour);
  EXPECT_EQ(a.intensity, b.intensity);
  EXPECT_EQ(a.range, b.range);
  EXPECT_EQ(a.innerConeAngle, b.innerConeAngle);
  EXPECT_EQ(a.outerConeAngle, b.outerConeAngle);
}

void expectNear(glm::vec3 got, glm::vec3 want) {
  EXPECT_NEAR(glm::distance(got, want), 0.0f, 1e-5f) << got.x << " " << got.y << " " << got.z;
}

std::vector<Light> at(const Scene& s, float t) {
  std::vector<Light> out;
  s.lightAnimation.sampleLights(s, t, out);
  return out;
}

// Node 0 carries point light 0 and moves from (1, 2, 3) to (5, 2, 3) between t = 0 and 2.
std::string movingPointLight() {
  return lightScene("moving", {{{0, 2}, "SCALAR"}, {{1, 2, 3, 5, 2, 3}, "VEC3"}},
                    R"("nodes": [{"translation": [1, 2, 3],
                                  "extensions": {"KHR_lights_punctual": {"light": 0}}}],
                       "scenes": [{"nodes": [0]}],
                       "animations": [{"channels": [)" +
                        channel(0, R"({"node": 0, "path": "translation"})") +
                        R"(], "samplers": [)" + sampler(0, 1) + "]}], " +
                        lights(R"({"type": "point", "range": 4})"));
}

TEST(LightAnimation, APointLightFollowsItsNodesLinearTranslation) {
  const Scene s = loadGltf(movingPointLight());
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_TRUE(s.lightAnimation.animated());
  EXPECT_EQ(s.lightAnimation.duration(), 2.0f);
  expectSame(at(s, 0.0f)[0], s.lights[0]);
  expectNear(at(s, 1.0f)[0].position, {3, 2, 3});
  expectNear(at(s, 0.5f)[0].position, {2, 2, 3});
  expectNear(at(s, 2.0f)[0].position, {5, 2, 3});
  expectNear(at(s, 7.0f)[0].position, {5, 2, 3});
  expectNear(at(s, -1.0f)[0].position, {1, 2, 3});
  EXPECT_EQ(at(s, 1.0f)[0].range, 4.0f);
}

// Node 0 (scale 2, turning 90° about +Y between t = 0 and 1) is the parent of node 1 at
// (0, 0, −2), which carries spot light 0 looking down −Z.
TEST(LightAnimation, ALightUnderARotatingParentTurnsWithIt) {
  const float h = 0.70710678f;
  const Scene s = loadGltf(lightScene("parent",
                                      {{{0, 1}, "SCALAR"}, {{0, 0, 0, 1, 0, h, 0, h}, "VEC4"}},
                                      R"("nodes": [{"scale": [2, 2, 2], "children": [1]},
                   {"translation": [0, 0, -2], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}],
         "animations": [{"channels": [)" + channel(0, R"({"node": 0, "path": "rotation"})") +
                                          R"(], "samplers": [)" + sampler(0, 1) + "]}], " +
                                          lights(R"({"type": "spot", "range": 5, "spot": {}})")));
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_EQ(s.lightAnimation.lights.size(), 1u);
  EXPECT_EQ(s.lightAnimation.lights[0].chain.size(), 2u) << "the parent and the light's node";
  expectSame(at(s, 0.0f)[0], s.lights[0]);
  expectNear(at(s, 0.0f)[0].position, {0, 0, -4});
  expectNear(at(s, 1.0f)[0].position, {-4, 0, 0});
  expectNear(at(s, 1.0f)[0].direction, {-1, 0, 0});
  const float r = 4.0f * h;
  expectNear(at(s, 0.5f)[0].position, {-r, 0, -r});
  expectNear(at(s, 0.5f)[0].direction, {-h, 0, -h});
  // Node scale leaves the light's range alone.
  EXPECT_EQ(at(s, 0.5f)[0].range, 5.0f);
}

// At t = 0 every track holds its node's rest value: the loader's lights, bit for bit, under
// a parent whose rotation is not exact in float and with scale on the light's node.
TEST(LightAnimation, AtRestValuesItGivesTheLoadersLightsBitForBit) {
  const Scene s = loadGltf(
      lightScene("rest",
                 {{{0, 1}, "SCALAR"},
                  {{1.5f, -2, 0.25f, 4, 0, 0}, "VEC3"},
                  {{0.5f, 0.5f, 0.5f, 0.5f, 0, 0, 0, 1}, "VEC4"}},
                 R"("nodes": [{"translation": [0.1, 0.2, 0.3],
                    "rotation": [0.4027322, 0.428839833, 0.222705975, -0.7773707], "children": [1]},
                   {"translation": [1.5, -2, 0.25], "rotation": [0.5, 0.5, 0.5, 0.5],
                    "scale": [2, 1, 0.5], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}],
         "animations": [{"channels": [)" +
                     channel(0, R"({"node": 1, "path": "translation"})") + "," +
                     channel(1, pointer("/nodes/1/rotation")) + R"(], "samplers": [)" +
                     sampler(0, 1) + "," + sampler(0, 2) + "]}], " +
                     lights(R"({"type": "spot", "range": 3, "spot": {"outerConeAngle": 0.5}})")));
  ASSERT_EQ(s.lightAnimation.lights.size(), 1u);
  ASSERT_EQ(s.lightAnimation.lights[0].chain.size(), 2u);
  EXPECT_EQ(s.lightAnimation.lights[0].chain[1].tracks.size(), 2u) << "by node and by pointer";
  expectSame(at(s, 0.0f)[0], s.lights[0]);
  expectSame(at(s, -3.0f)[0], s.lights[0]);
  EXPECT_NE(at(s, 1.0f)[0].position, s.lights[0].position);
}

// STEP keys through KHR_animation_pointer: intensity 1, 4, 9 at t = 0, 1, 2 on light 0; the
// node's translation by pointer, STEP too; colour LINEAR.
TEST(LightAnimation, StepKeysHoldUntilTheNextKey) {
  const Scene s = loadGltf(
      lightScene("step",
                 {{{0, 1, 2}, "SCALAR"},
                  {{1, 4, 9}, "SCALAR"},
                  {{0, 0, 0, 0, 6, 0, 0, 6, 6}, "VEC3"},
                  {{1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3"}},
                 R"("nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}],
         "animations": [{"channels": [)" +
                     channel(0, pointer("/extensions/KHR_lights_punctual/lights/0/intensity")) +
                     "," + channel(1, pointer("/nodes/0/translation")) + "," +
                     channel(2, pointer("/extensions/KHR_lights_punctual/lights/0/color")) +
                     R"(], "samplers": [)" + sampler(0, 1, "STEP") + "," + sampler(0, 2, "STEP") +
                     "," + sampler(0, 3) + "]}], " + lights(R"({"type": "point"})")));
  EXPECT_EQ(at(s, 0.5f)[0].intensity, 1.0f);
  EXPECT_EQ(at(s, 1.0f)[0].intensity, 4.0f);
  EXPECT_EQ(at(s, 1.99f)[0].intensity, 4.0f);
  EXPECT_EQ(at(s, 2.0f)[0].intensity, 9.0f);
  EXPECT_EQ(at(s, 1.5f)[0].position, glm::vec3(0, 6, 0));
  EXPECT_EQ(at(s, 2.5f)[0].position, glm::vec3(0, 6, 6));
  EXPECT_EQ(s.ignoredExtensions, std::vector<std::string>{}) << "KHR_animation_pointer is used";
  expectNear(at(s, 0.5f)[0].colour, {0.5f, 0.5f, 0});
  expectNear(at(s, 1.25f)[0].colour, {0, 0.75f, 0.25f});
}

// Spot light 0: intensity a cubic spline from 2 to 6 over t in [0, 2] with zero tangents
// (a smoothstep); its inner cone angle animated from 0.1 to 0.6, past its still outer 0.5.
TEST(LightAnimation, CubicSplinesAndConesThatCrossStayValid) {
  const Scene s = loadGltf(lightScene(
      "cubic", {{{0, 2}, "SCALAR"}, {{0, 2, 0, 0, 6, 0}, "SCALAR"}, {{0.1f, 0.6f}, "SCALAR"}},
      R"("nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}],
         "animations": [{"channels": [)" +
          channel(0, pointer("/extensions/KHR_lights_punctual/lights/0/intensity")) + "," +
          channel(1, pointer("/extensions/KHR_lights_punctual/lights/0/spot/innerConeAngle")) +
          R"(], "samplers": [)" + sampler(0, 1, "CUBICSPLINE") + "," + sampler(0, 2) + "]}], " +
          lights(R"({"type": "spot", "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}})")));
  EXPECT_NEAR(at(s, 1.0f)[0].intensity, 4.0f, 1e-5f);
  EXPECT_NEAR(at(s, 0.5f)[0].intensity, 2.0f + 4.0f * (3 * 0.0625f - 2 * 0.015625f), 1e-5f);
  EXPECT_NEAR(at(s, 0.8f)[0].innerConeAngle, 0.3f, 1e-5f);
  const Light end = at(s, 2.0f)[0];
  EXPECT_EQ(end.outerConeAngle, 0.5f);
  EXPECT_EQ(end.innerConeAngle, std::nextafter(0.5f, 0.0f)) << "kept below the outer angle";
}

// Light 0 on nodes 0 and 1 (two Scene lights), its intensity animated over t in [0, 1];
// node 1 moves over [0, 3]; light 1 on node 2 is still.
TEST(LightAnimation, ChangedListsOnlyTheLightsThatChanged) {
  const Scene s = loadGltf(lightScene(
      "changed",
      {{{0, 1}, "SCALAR"}, {{1, 3}, "SCALAR"}, {{0, 3}, "SCALAR"}, {{0, 0, 0, 3, 0, 0}, "VEC3"}},
      R"("nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}},
                   {"extensions": {"KHR_lights_punctual": {"light": 0}}},
                   {"translation": [0, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}}],
         "scenes": [{"nodes": [0, 1, 2]}],
         "animations": [{"channels": [)" +
          channel(0, pointer("/extensions/KHR_lights_punctual/lights/0/intensity")) +
          R"(], "samplers": [)" + sampler(0, 1) + R"(]},
                        {"channels": [)" +
          channel(0, R"({"node": 1, "path": "translation"})") + R"(], "samplers": [)" +
          sampler(2, 3) + "]}], " + lights(R"({"type": "point"}, {"type": "point"})")));
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lightAnimation.duration(), 3.0f) << "both animations, playing together";
  std::vector<Light> out;
  std::vector<int> changed{7};
  s.lightAnimation.sampleLights(s, 0.0f, out, &changed);
  EXPECT_EQ(changed, std::vector<int>{}) << "at rest: Scene::lights";
  s.lightAnimation.sampleLights(s, 0.5f, out, &changed);
  EXPECT_EQ(changed, (std::vector<int>{0, 1}));
  EXPECT_EQ(out[0].intensity, 2.0f);
  EXPECT_EQ(out[1].intensity, 2.0f);
  expectNear(out[0].position, {0, 0, 0});
  expectNear(out[1].position, {0.5f, 0, 0});
  expectSame(out[2], s.lights[2]);
  s.lightAnimation.sampleLights(s, 0.5f, out, &changed);
  EXPECT_EQ(changed, std::vector<int>{}) << "the same time again";
  s.lightAnimation.sampleLights(s, 1.5f, out, &changed);
  EXPECT_EQ(changed, (std::vector<int>{0, 1}));
  s.lightAnimation.sampleLights(s, 2.5f, out, &changed);
  EXPECT_EQ(changed, (std::vector<int>{1})) << "light 0's intensity stays at its last key";
  EXPECT_EQ(out[0].intensity, 3.0f);
  expectNear(out[1].position, {2.5f, 0, 0});
}

TEST(LightAnimation, ScenesWithoutLightAnimationsAreNotAnimated) {
  const Scene s = loadGltf(testing::animatedScene("camera_only"));
  EXPECT_FALSE(s.lightAnimation.animated());
  EXPECT_EQ(s.lightAnimation.duration(), 0.0f);
  // A material pointer moves no light and is ignored.
  const Scene m = loadGltf(lightScene(
      "material", {{{0, 1}, "SCALAR"}, {{0, 1}, "SCALAR"}},
      R"("nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}], "materials": [{}],
         "animations": [{"channels": [)" +
          channel(0, pointer("/materials/0/pbrMetallicRoughness/roughnessFactor")) +
          R"(], "samplers": [)" + sampler(0, 1) + "]}], " + lights(R"({"type": "point"})")));
  EXPECT_FALSE(m.lightAnimation.animated());
}

struct BadCase {
  const char* pointer;
  std::vector<float> times, values;
  const char* type;
  const char* problem;
};

TEST(LightAnimation, BadTracksAndPointersAreRefused) {
  const std::string base = "/extensions/KHR_lights_punctual/lights/";
  const BadCase cases[] = {
      {"5/intensity",
       {0, 1},
       {1, 2},
       "SCALAR",
       "pointer '/extensions/KHR_lights_punctual/lights/5/intensity': light 5 does not exist"},
      {"x/intensity",
       {0, 1},
       {1, 2},
       "SCALAR",
       "pointer '/extensions/KHR_lights_punctual/lights/x/intensity': no light index"},
      {"0/spot/innerConeAngle",
       {0, 1},
       {0, 0.1f},
       "SCALAR",
       "pointer '/extensions/KHR_lights_punctual/lights/0/spot/innerConeAngle': light 0 is not a "
       "spot light"},
      {"0/colour",
       {0, 1},
       {1, 1, 1, 0, 0, 0},
       "VEC3",
       "pointer '/extensions/KHR_lights_punctual/lights/0/colour': light 0 has no animatable "
       "property there (color, intensity, range, spot/innerConeAngle, spot/outerConeAngle)"},
      {"0/intensity", {0, 2, 1}, {1, 2, 3}, "SCALAR", "key times must increase"},
      {"0/intensity", {0, NAN}, {1, 2}, "SCALAR", "key times must be finite and >= 0"},
      {"0/color", {0, 1}, {1, 1, 1}, "VEC3", "3 values for 2 keys, expected 6"},
      {"0/range", {0, 1}, {1, -2}, "SCALAR", "values must not be negative"},
      {"0/intensity", {0, 1}, {1, INFINITY}, "SCALAR", "values must be finite"},
  };
  for (const BadCase& c : cases) {
    const std::string path =
        lightScene("bad", {{c.times, "SCALAR"}, {c.values, c.type}},
                   R"("nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
           "scenes": [{"nodes": [0]}],
           "animations": [{"channels": [)" +
                       channel(0, pointer(base + c.pointer)) + R"(], "samplers": [)" +
                       sampler(0, 1) + "]}], " + lights(R"({"type": "point"})"));
    try {
      loadGltf(path);
      ADD_FAILURE() << c.pointer << " accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": animation 0: channel 0: " + c.problem);
    }
  }
}

TEST(LightAnimation, AnimatedNodesWithAMatrixAreRefused) {
  const std::string path = lightScene("matrix", {{{0, 1}, "SCALAR"}, {{0, 0, 0, 1, 0, 0}, "VEC3"}},
                                      R"("nodes": [{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],
                    "extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}],
         "animations": [{"channels": [)" + channel(0, pointer("/nodes/0/translation")) +
                                          R"(], "samplers": [)" + sampler(0, 1) + "]}], " +
                                          lights(R"({"type": "point"})"));
  try {
    loadGltf(path);
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": animation 0: channel 0: node 0 has a matrix and cannot be animated");
  }
}

// The shared AnimateAllTheThings asset: lights 0 (directional, node 4), 1 (spot, node 5),
// 2 (spot, node 6, still) and 3 (spot, node 12) in walk order, animated by KHR_animation_pointer
// channels of animation 0. The expected values are its accessors' keys interpolated by hand
// (LINEAR; t = 2.5 lies between keys 75 and 76 of the 301-key tracks, 22 and 23 of light 3's
// range and 55 and 56 of its cone and intensity tracks, whose two keys are equal).
TEST(LightAnimation, AnimateAllTheThingsChangesItsSpotLights) {
  const fs::path file =
      fs::path(MANYLIGHT_SHARED_SCENES) / "AnimateAllTheThings/24_animation_pointer.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << "no " << file << " (the shared scenes are absent)";
  const Scene s = loadGltf(file.string());
  ASSERT_EQ(s.lights.size(), 4u);
  ASSERT_EQ(s.lightAnimation.lights.size(), 3u) << "light 2 is still";
  EXPECT_FLOAT_EQ(s.lightAnimation.duration(), 10.016666412353516f);
  const std::vector<Light> a = at(s, 2.5f);
  expectSame(a[2], s.lights[2]);
  auto near = [](float got, double want) { EXPECT_NEAR(got, want, 1e-5 * std::abs(want)); };
  near(a[1].intensity, 13.414008868927958);
  expectNear(a[1].colour, {0.23117388983200307f, 0.543167558024552f, 1.0f});
  near(a[1].outerConeAngle, 0.20073269086430767);
  near(a[1].innerConeAngle, 0.008727795442267058);
  near(a[3].range, 7.669603431695757);
  near(a[3].intensity, 79.48229217529297);
  expectNear(a[3].colour, {0.768064329242202f, 0.8326735496520996f, 0.2251921476294157f});
  near(a[3].outerConeAngle, 0.09599310904741287);
  near(a[3].innerConeAngle, 0.06981316953897476);
  const std::vector<Light> b = at(s, 5.0f);
  near(b[3].intensity, 79.3268854741161);
  near(b[3].outerConeAngle, 0.09620848021002049);
  near(b[1].outerConeAngle, 0.6806574574762284);
  // Past the last key: the last keys.
  const std::vector<Light> c = at(s, 20.0f);
  near(c[1].intensity, 3.1415927410125732);
  EXPECT_EQ(c[3].colour, glm::vec3(1, 0, 0));
  EXPECT_EQ(c[3].range, 10.0f);
  near(c[1].innerConeAngle, 0.09905361384153366);
}

}  // namespace
}  // namespace manylight
