// Camera animations (scene/camera_animation.h): read from glTF, evaluated with each
// interpolation, checked, and kept by baked scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "bake/baked_file.h"
#include "scene/camera_animation.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight {
namespace {

using testing::animatedScene;
using testing::testFolder;

glm::vec3 positionAt(const Camera& c, float t) { return glm::vec3(animatedCameraWorld(c, t)[3]); }

TEST(Animation, TheLoaderReadsTheChainAndItsTracks) {
  const Scene s = loadGltf(animatedScene("linear"));
  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& c = s.cameras[0];
  ASSERT_EQ(c.animation.chain.size(), 2u) << "the parent and the camera's node";
  EXPECT_EQ(c.animation.duration, 2.0f);
  EXPECT_EQ(c.animation.chain[1].tracks.size(), 2u);
  // Linear translation, under the parent's (1, 0, 0); clamped outside the keys.
  EXPECT_NEAR(glm::distance(positionAt(c, 0.0f), glm::vec3(1, 0, 5)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(positionAt(c, 0.5f), glm::vec3(1, 0, 7.5f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(positionAt(c, 1.5f), glm::vec3(1, 0, 12.5f)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(positionAt(c, 9.0f), glm::vec3(1, 0, 15)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(positionAt(c, -1.0f), glm::vec3(1, 0, 5)), 0.0f, 1e-5f);
  // Step rotation: looking down −Z until t = 1, then turned 90° about +Y (looking down −X).
  const glm::vec3 before = -glm::vec3(animatedCameraWorld(c, 0.99f)[2]);
  const glm::vec3 after = -glm::vec3(animatedCameraWorld(c, 1.0f)[2]);
  EXPECT_NEAR(glm::distance(before, glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::distance(after, glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  // The still camera is the rest pose: the node without its animation.
  EXPECT_NEAR(glm::distance(glm::vec3(c.world[3]), glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
}

TEST(Animation, CubicSplinesFollowHermiteCurves) {
  Camera c;
  AnimatedNode n;
  AnimationTrack t;
  t.interpolation = AnimationTrack::CubicSpline;
  t.times = {0.0f, 2.0f};
  // Per key: in-tangent, value, out-tangent. Zero tangents: smoothstep from 0 to 4 in x.
  t.values = {0, 0, 0, 0, 0, 0, 0, 0, 0, /**/ 0, 0, 0, 4, 0, 0, 0, 0, 0};
  n.tracks.push_back(t);
  c.animation.chain.push_back(n);
  c.animation.duration = 2.0f;
  EXPECT_NEAR(positionAt(c, 1.0f).x, 2.0f, 1e-5f);
  EXPECT_NEAR(positionAt(c, 0.5f).x, 4.0f * (3 * 0.0625f - 2 * 0.015625f), 1e-5f);
  // A tangent of 4 units/s at the start: the curve leaves faster.
  c.animation.chain[0].tracks[0].values[6] =
      4.0f;  // key 0: in-tangent 0–2, value 3–5, out-tangent 6–8
  const float u = 0.25f, dt = 2.0f;
  const float want = dt * (u * u * u - 2 * u * u + u) * 4.0f + (-2 * u * u * u + 3 * u * u) * 4.0f;
  EXPECT_NEAR(positionAt(c, 0.5f).x, want, 1e-5f);
}

TEST(Animation, BrokenTracksAreRefused) {
  const std::string path = animatedScene("decreasing", "LINEAR", 3.0f);  // times 0, 3, 2
  try {
    loadGltf(path);
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": animation 0: channel 0: key times must increase");
  }
  const std::string unknown = animatedScene("unknown", "BEZIER");
  try {
    loadGltf(unknown);
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              unknown + ": animation 0: channel 0: unknown interpolation 'BEZIER'");
  }
  AnimationTrack t;
  t.times = {0.0f, 1.0f};
  t.values = {1, 2, 3};
  EXPECT_EQ(checkTrack(t), "3 values for 2 keys, expected 6");
}

TEST(Animation, BakedScenesKeepIt) {
  const Scene s = loadGltf(animatedScene("baked"));
  const std::string path = (testFolder() / "animated.mlbake").string();
  writeBakedScene(path, bakeScene(s, {}));
  const BakedScene b = readBakedScene(path);
  ASSERT_EQ(b.scene.cameras.size(), 1u);
  EXPECT_EQ(b.scene.cameras[0].animation.duration, 2.0f);
  for (float t : {0.0f, 0.3f, 1.0f, 1.7f, 2.0f}) {
    EXPECT_EQ(animatedCameraWorld(b.scene.cameras[0], t), animatedCameraWorld(s.cameras[0], t))
        << t;
  }
}

}  // namespace
}  // namespace manylight
