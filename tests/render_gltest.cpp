// The GPU reference method against the CPU double-precision oracle, on generated scenes.
#include <gtest/gtest.h>

#include "gl/limits.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/gl_support.h"
#include "tests/oracle.h"
#include "tests/oracle_compare.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

struct OracleCase {
  const char* name;
  int lights;
  bool mix, withRange, textured, specular;
  int camera;
};

// One suite: the oracle cases are parameterised by scene, the other tests take no parameter.
class Render : public ::testing::TestWithParam<OracleCase> {};

TEST_P(Render, ReferenceMatchesOracle) {
  const OracleCase& p = GetParam();
  context();
  RoomOptions o;
  o.lightCount = p.lights;
  o.mix = p.mix;
  o.withRange = p.withRange;
  o.textured = p.textured;
  o.specular = p.specular;
  const Scene scene = loadGltf(roomScene(o));
  RenderRequest request;
  request.width = 160;
  request.height = 120;
  request.camera = p.camera;
  request.ambient = glm::vec3(0.02f, 0.03f, 0.04f);
  expectMatchesOracle(scene, request, p.name);
}

INSTANTIATE_TEST_SUITE_P(
    , Render,
    ::testing::Values(OracleCase{"one_point", 1, false, false, false, false, 0},
                      OracleCase{"seven_mixed_range_textured", 7, true, true, true, false, 0},
                      OracleCase{"sixty_four_mixed_specular", 64, true, true, true, true, 0},
                      OracleCase{"thousand_mixed_no_range", 1000, true, false, true, false, 0},
                      OracleCase{"thousand_mixed_range_specular", 1000, true, true, false, true, 0},
                      OracleCase{"orthographic_seven", 7, true, true, true, true, 1}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(Render, DefaultRigLightsASceneWithoutLights) {
  context();
  RoomOptions o;
  o.lightCount = 0;
  const Scene scene = loadGltf(roomScene(o));
  RenderRequest request;
  request.width = 96;
  request.height = 72;
  const RenderOutcome gpu = expectMatchesOracle(scene, request, "default_rig");
  EXPECT_TRUE(gpu.defaultRig);
  EXPECT_EQ(gpu.lightCount, 3u);
}

TEST_F(Render, FramingShowsTheWholeSceneWithoutCamera) {
  context();
  // A box alone, no camera, no lights: framed from the 3/4 view and lit by the rig.
  GltfBuilder b;
  b.addBox({0.0f, 0.0f, 0.0f}, {1.0f, 2.0f, 1.0f}, b.addMaterial({}));
  const std::string path = (testFolder() / "box.gltf").string();
  b.write(path);
  const Scene scene = loadGltf(path);
  RenderRequest request;
  request.width = 64;
  request.height = 64;
  const RenderOutcome out = renderScene(scene, request);
  EXPECT_TRUE(out.framed);
  // Nothing touches the border (5% margin), and the box covers a good part of the image.
  int covered = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool hit = out.image.pixel(x, y)[3] > 0.0f;
      covered += hit;
      if (x == 0 || y == 0 || x == 63 || y == 63) {
        EXPECT_FALSE(hit) << x << "," << y;
      }
    }
  }
  EXPECT_GT(covered, 64 * 64 / 8);
}

TEST_F(Render, ManyPassesEqualTheOracle) {
  // Long light lists are split into additive passes; passes of 37 lights (an odd size, so
  // pass boundaries fall inside each light type's group) must add up to the exact image.
  context();
  // The automatic pass size keeps a pass under the evaluation bound and never below 1.
  for (int pixels : {1, 160 * 120, 640 * 480, 16384 * 16384}) {
    const int perPass = ReferenceMethod::lightsPerPass(pixels);
    EXPECT_GE(perPass, 1);
    if (perPass > 1) {
      EXPECT_LE(double(perPass) * pixels, double(ReferenceMethod::kEvaluationsPerPass));
    }
  }
  RoomOptions o;
  o.lightCount = 1000;
  const Scene scene = loadGltf(roomScene(o));
  RenderRequest request;
  request.width = 160;
  request.height = 120;
  request.lightsPerPass = 37;
  const RenderOutcome gpu = expectMatchesOracle(scene, request, "many_passes");
  EXPECT_EQ(gpu.frame.lightingPasses, (1000 + 36) / 37);
}

TEST_F(Render, SmallImagesWithManyLightsStayWithinTheLoopLimit) {
  // An 8×8 image would take all 300,000 lights in one pass by the evaluation bound alone;
  // llvmpipe would then end the loop at 65,535 iterations and drop most lights silently.
  context();
  RoomOptions o;
  o.lightCount = 1;
  o.textured = false;
  Scene scene = loadGltf(roomScene(o));
  scene.lights.assign(300000, scene.lights[0]);
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    scene.lights[i].type = LightType::Point;
    scene.lights[i].position = {-4.0f + 8.0f * float(i % 97) / 96.0f, 2.0f + float(i % 13) / 13.0f,
                                -2.0f};
    scene.lights[i].intensity = 1e-4f;
    scene.lights[i].range = 0.0f;
  }
  RenderRequest request;
  request.width = 8;
  request.height = 8;
  const RenderOutcome automatic = renderScene(scene, request);
  request.lightsPerPass = 1000;
  const RenderOutcome small = renderScene(scene, request);
  EXPECT_GT(automatic.frame.lightingPasses, 1);
  int lit = 0;
  for (std::size_t i = 0; i < small.image.rgba.size(); ++i) {
    if (i % 4 == 3 || small.image.rgba[i] <= 0.0f) continue;
    ++lit;
    EXPECT_NEAR(automatic.image.rgba[i], small.image.rgba[i], 1e-4 * small.image.rgba[i])
        << "value " << i;
  }
  EXPECT_GT(lit, 0);
}

}  // namespace
}  // namespace manylight::testing

namespace manylight::testing {
namespace {

TEST_F(Render, AGBufferPastTheContextsLimitsNamesTheLimit) {
  context();
  const gl::RenderSizeLimits limits = gl::renderSizeLimits();
  EXPECT_GE(limits.maxTextureSize, 1024);  // OpenGL 3.3's minimum
  EXPECT_GE(limits.maxRenderbufferSize, 1024);
  const int side = limits.maxTextureSize + 1;
  EXPECT_EQ(gl::renderSizeExceeded(16, 16), "");
  EXPECT_EQ(gl::renderSizeExceeded(16, side),
            "exceeds the context's GL_MAX_TEXTURE_SIZE " + std::to_string(side - 1));
  try {
    GBuffer g(side, 1);
    ADD_FAILURE() << "a " << side << "x1 G-buffer was made";
  } catch (const gl::GlError& e) {
    EXPECT_EQ(std::string(e.what()),
              "image size " + std::to_string(side) + "x1 " + gl::renderSizeExceeded(side, 1));
  }
}

}  // namespace
}  // namespace manylight::testing
