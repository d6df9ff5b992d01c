// glTF materials on the GPU against the CPU oracle, one feature at a time: textured
// metallic-roughness, emissive, normal-mapped, masked, two-sided, a second UV set with a
// texture transform, occlusion; and the white furnace (ambient light alone).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "generators/scene_builder.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/cli_support.h"
#include "tests/gl_support.h"
#include "tests/oracle_compare.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

// An 8×8 checker of texels `a` and `b` (RGBA8), in 2×2 blocks.
BuilderTexture checker(glm::u8vec4 a, glm::u8vec4 b) {
  BuilderTexture t;
  t.width = t.height = 8;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const glm::u8vec4 c = ((x / 2) + (y / 2)) % 2 ? a : b;
      t.rgba.insert(t.rgba.end(), {c.r, c.g, c.b, c.a});
    }
  }
  return t;
}

void setBaseTexture(BuilderMaterial& m, const BuilderTexture& t) {
  m.textureWidth = t.width;
  m.textureHeight = t.height;
  m.textureRgba = t.rgba;
}

// A unit-normal tangent-space vector as a normal texture stores it.
glm::u8vec4 normalTexel(glm::vec3 n) {
  n = glm::normalize(n);
  auto code = [](float x) { return std::uint8_t(std::lround((x * 0.5f + 0.5f) * 255.0f)); };
  return {code(n.x), code(n.y), code(n.z), 255};
}

// A 2×2 plane at the origin facing +Y carrying `m`, seen from above at an angle, lit by a
// point light and a directional light (and a floor below it, for what masks let through).
Scene planeScene(const std::string& name, const BuilderMaterial& m, bool secondUvs = false,
                 glm::vec3 eye = {0.3f, 2.0f, 1.6f}) {
  GltfBuilder b;
  const int material = b.addMaterial(m);
  if (secondUvs) {
    b.addPlaneWithSecondUvs({0, 0, 0}, {2, 2}, material);
  } else {
    b.addPlane({0, 0, 0}, {2, 2}, material);
  }
  BuilderMaterial floor;
  floor.baseColor = {0.2f, 0.5f, 0.3f, 1.0f};
  b.addPlane({0, -0.4f, 0}, {6, 6}, b.addMaterial(floor));
  Light point;
  point.position = {0.4f, 1.2f, 0.6f};
  point.intensity = 2.0f;
  point.colour = {1.0f, 0.9f, 0.8f};
  b.addLight(point);
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
  sun.intensity = 1.5f;
  b.addLight(sun);
  b.addPerspectiveCamera(eye, {0, 0, 0}, 0.9f);
  const std::string path = (testFolder() / (name + ".gltf")).string();
  b.write(path);
  return loadGltf(path);
}

// A 2×2 plane carrying `m` under `light`, seen from straight above (near its centre): for
// checks of one pixel. Returns the loaded scene.
Scene topDownPlane(const std::string& name, const BuilderMaterial& m, const Light& light) {
  GltfBuilder b;
  b.addPlane({0, 0, 0}, {2, 2}, b.addMaterial(m));
  b.addLight(light);
  b.addPerspectiveCamera({0, 2, 0.5f}, {0, 0, 0}, 0.6f);
  const std::string path = (testFolder() / (name + ".gltf")).string();
  b.write(path);
  return loadGltf(path);
}

RenderRequest request() {
  RenderRequest r;
  r.width = 160;
  r.height = 120;
  r.ambient = glm::vec3(0.05f, 0.06f, 0.07f);
  return r;
}

TEST(Material, TexturedMetallicRoughnessMatchesTheOracle) {
  context();
  BuilderMaterial m;
  m.metallic = 1.0f;
  m.roughness = 1.0f;
  setBaseTexture(m, checker({230, 180, 60, 255}, {90, 140, 210, 255}));
  // B metalness 0 or 1, G roughness 0.55 or 0.9: metal and dielectric, smoother and rough.
  // Phong exponents stay near 20: llvmpipe's pow is an approximation whose relative error
  // grows with the exponent (0.5-1% in the wings of a highlight of exponent 245). And
  // llvmpipe filters with 8-bit weights, which moves the exponent between texels, so this
  // texture is sampled NEAREST (filtering is checked by the other textures).
  m.metallicRoughness = checker({0, 140, 255, 255}, {0, 230, 0, 255});
  m.metallicRoughness.nearest = true;
  const Scene scene = planeScene("mr", m);
  ASSERT_GE(scene.materials[0].metallicRoughnessTexture.texture, 0);
  EXPECT_FALSE(scene.textures[scene.materials[0].metallicRoughnessTexture.texture].srgb);
  expectMatchesOracle(scene, request(), "material_mr");
}

TEST(Material, SpecularGlossinessMatchesTheOracle) {
  context();
  BuilderMaterial m;
  m.specularGlossiness = true;
  m.baseColor = {0.8f, 0.7f, 0.6f, 1.0f};
  m.specularFactor = {0.9f, 0.8f, 0.7f};
  m.glossiness = 0.9f;
  setBaseTexture(m, checker({230, 180, 60, 255}, {90, 140, 210, 255}));
  // sRGB specular colour, linear glossiness 0.5 or 0.2 in A (exponents stay small, as in
  // the metallic-roughness test, and NEAREST for the same reason).
  m.specularGlossinessTexture = checker({200, 200, 200, 128}, {60, 90, 40, 51});
  m.specularGlossinessTexture.nearest = true;
  const Scene scene = planeScene("sg", m);
  ASSERT_TRUE(scene.materials[0].specularGlossiness);
  EXPECT_TRUE(scene.textures[scene.materials[0].metallicRoughnessTexture.texture].srgb);
  expectMatchesOracle(scene, request(), "material_sg");
}

TEST(Material, EmissiveTextureTimesFactorAndStrengthMatchesTheOracle) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.3f, 0.3f, 0.3f, 1.0f};
  m.emissive = {1.0f, 0.5f, 0.25f};
  m.emissiveStrength = 3.0f;
  m.emissiveTexture = checker({255, 255, 255, 255}, {40, 200, 90, 255});
  const Scene scene = planeScene("emissive", m);
  EXPECT_FLOAT_EQ(scene.materials[0].emissive.r, 3.0f);
  expectMatchesOracle(scene, request(), "material_emissive");
}

TEST(Material, NormalMappedMatchesTheOracle) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.8f, 0.8f, 0.8f, 1.0f};
  m.normal = checker(normalTexel({0.4f, -0.3f, 0.85f}), normalTexel({-0.3f, 0.35f, 0.9f}));
  m.normalScale = 0.8f;
  const Scene scene = planeScene("normal", m);
  ASSERT_FALSE(scene.meshes[0].primitives[0].tangents.empty());
  expectMatchesOracle(scene, request(), "material_normal");
}

TEST(Material, MaskedPixelsShowWhatLiesBehind) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.9f, 0.3f, 0.2f, 1.0f};
  m.alphaMode = "MASK";
  m.alphaCutoff = 0.5f;
  setBaseTexture(m, checker({255, 255, 255, 255}, {255, 255, 255, 40}));
  m.textureNearest = true;  // so the cutoff falls on texel edges, not between filter weights
  const Scene scene = planeScene("mask", m);
  EXPECT_EQ(scene.materials[0].alphaMode, AlphaMode::Mask);
  expectMatchesOracle(scene, request(), "material_mask");
}

TEST(Material, TwoSidedBackFacesAreShadedAndOneSidedCulled) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.7f, 0.6f, 0.5f, 1.0f};
  m.doubleSided = true;
  m.roughness = 0.5f;
  // Seen from below: the double-sided plane shows its back, lit with the flipped normal.
  const Scene twoSided = planeScene("two_sided", m, false, {0.3f, -0.3f, 2.0f});
  expectMatchesOracle(twoSided, request(), "material_two_sided");
  m.doubleSided = false;
  const Scene oneSided = planeScene("one_sided", m, false, {0.3f, -0.3f, 2.0f});
  expectMatchesOracle(oneSided, request(), "material_one_sided");
}

TEST(Material, SecondUvSetWithTextureTransformMatchesTheOracle) {
  context();
  BuilderMaterial m;
  setBaseTexture(m, checker({230, 180, 60, 255}, {90, 140, 210, 255}));
  m.occlusion = checker({90, 0, 0, 255}, {255, 0, 0, 255});
  m.occlusion.texCoord = 1;
  m.occlusion.transform = true;
  m.occlusion.offset = {0.25f, 0.1f};
  m.occlusion.scale = {1.5f, 0.75f};
  m.occlusion.rotation = 0.4f;
  m.occlusionStrength = 0.9f;
  const Scene scene = planeScene("second_uv", m, true);
  const Primitive& p = scene.meshes[0].primitives[0];
  ASSERT_EQ(p.texcoords1.size(), p.positions.size());
  EXPECT_EQ(scene.materials[0].occlusionTexture.texCoord, 1);
  RenderRequest r = request();
  r.ambient = glm::vec3(0.4f, 0.3f, 0.2f);  // occlusion darkens the ambient term only
  expectMatchesOracle(scene, r, "material_second_uv");
}

// Blended primitives are lit as opaque ones are, then composited over what lies behind them,
// farthest first: a half-transparent plane over the floor, and a quarter-transparent box
// over both (alphas exact in float, so coverage compares exactly).
TEST(Material, BlendedPrimitivesAreLitAndCompositedBackToFront) {
  context();
  BuilderMaterial glass;
  glass.baseColor = {0.3f, 0.6f, 0.9f, 0.5f};
  glass.roughness = 0.6f;
  glass.alphaMode = "BLEND";
  GltfBuilder b;
  b.addPlane({0, 0, 0}, {1.4f, 1.4f}, b.addMaterial(glass));
  BuilderMaterial tinted;
  tinted.baseColor = {0.9f, 0.4f, 0.2f, 0.25f};
  tinted.alphaMode = "BLEND";
  b.addBox({0.3f, 0.35f, 0.2f}, {0.5f, 0.5f, 0.5f}, b.addMaterial(tinted));
  BuilderMaterial floor;
  floor.baseColor = {0.2f, 0.5f, 0.3f, 1.0f};
  b.addPlane({0, -0.4f, 0}, {6, 6}, b.addMaterial(floor));
  Light point;
  point.position = {0.4f, 1.2f, 0.6f};
  point.intensity = 2.0f;
  b.addLight(point);
  b.addPerspectiveCamera({0.3f, 2.0f, 1.6f}, {0, 0, 0}, 0.9f);
  const std::string path = (testFolder() / "blend.gltf").string();
  b.write(path);
  const Scene scene = loadGltf(path);
  for (const Method method : {Method::Reference, Method::Lightcuts}) {
    RenderRequest r = request();
    r.method = method;
    r.lightcuts.mode = ErrorMode::Total;
    r.lightcuts.error = 1e-4f;
    const RenderOutcome out = expectMatchesOracle(scene, r, "material_blend");
    EXPECT_EQ(out.frame.lightingPasses, 3);  // the opaque frame and two layers
  }
}

// White furnace: ambient A and no light give each opaque material A × (albedo + specular),
// metals included.
TEST(Material, AmbientAloneGivesEachMaterialItsReflectance) {
  context();
  struct Case {
    float metallic, roughness;
    glm::vec3 reflectance;  // albedo + ks for base colour (0.9, 0.6, 0.3)
  };
  const glm::vec3 base(0.9f, 0.6f, 0.3f);
  const Case cases[] = {{1.0f, 0.4f, base},
                        {0.0f, 1.0f, base},
                        {0.0f, 0.25f, base + glm::vec3(0.04f * 0.75f)},
                        {0.5f, 0.5f, base * 0.5f + (0.5f * 0.04f + 0.5f * base) * 0.75f}};
  for (const Case& c : cases) {
    BuilderMaterial m;
    m.baseColor = glm::vec4(base, 1.0f);
    m.metallic = c.metallic;
    m.roughness = c.roughness;
    Light off;
    off.intensity = 0.0f;  // a light that gives nothing, so no default rig stands in
    RenderRequest r;
    r.width = r.height = 16;
    r.ambient = glm::vec3(0.5f);
    const RenderOutcome out = renderScene(topDownPlane("furnace", m, off), r);
    const float* px = out.image.pixel(8, 8);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(px[ch], 0.5f * c.reflectance[ch], 1e-3f * c.reflectance[ch])
          << "metallic " << c.metallic << " roughness " << c.roughness << " channel " << ch;
    }
  }
}

// The tangent frame's orientation: a normal texture that tilts towards +u (tangent) or
// towards the top of the image (−v, the bitangent) brightens a surface lit from that side.
TEST(Material, NormalTexturesTiltTowardsPlusUAndTheImageTop) {
  context();
  auto centre = [](glm::vec3 tilt, glm::vec3 lightDir) {
    BuilderMaterial m;
    m.normal = checker(normalTexel(tilt), normalTexel(tilt));
    GltfBuilder b;
    b.addPlane({0, 0, 0}, {2, 2}, b.addMaterial(m));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = -glm::normalize(lightDir);
    b.addLight(sun);
    b.addPerspectiveCamera({0, 2, 0.01f}, {0, 0, 0}, 0.6f);
    const std::string path = (testFolder() / "tilt.gltf").string();
    b.write(path);
    RenderRequest r;
    r.width = r.height = 16;
    return renderScene(loadGltf(path), r).image.pixel(8, 8)[0];
  };
  // The builder's plane: u runs along +X, v along +Z (so the image's top is −Z), normal +Y.
  const glm::vec3 towardsPlusX(1, 1, 0), towardsMinusZ(0, 1, -1);
  const float flat = centre({0, 0, 1}, towardsPlusX);
  EXPECT_GT(centre({0.5f, 0, 0.866f}, towardsPlusX), 1.3f * flat);
  EXPECT_LT(centre({-0.5f, 0, 0.866f}, towardsPlusX), 0.7f * flat);
  EXPECT_GT(centre({0, 0.5f, 0.866f}, towardsMinusZ), 1.3f * flat);
  EXPECT_LT(centre({0, -0.5f, 0.866f}, towardsMinusZ), 0.7f * flat);
}

TEST(Material, UnlitShowsItsBaseColour) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.25f, 0.5f, 0.75f, 1.0f};
  m.unlit = true;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0, -1, 0};
  sun.intensity = 5.0f;
  const Scene scene = topDownPlane("unlit", m, sun);
  RenderRequest r;
  r.width = r.height = 16;
  r.ambient = glm::vec3(0.3f);
  for (const Method method : {Method::Reference, Method::Lightcuts}) {
    r.method = method;
    const float* px = renderScene(scene, r).image.pixel(8, 8);
    EXPECT_FLOAT_EQ(px[0], 0.25f);
    EXPECT_FLOAT_EQ(px[1], 0.5f);
    EXPECT_FLOAT_EQ(px[2], 0.75f);
    EXPECT_FLOAT_EQ(px[3], 1.0f);
  }
}

// A LINE_STRIP without normals across the view, drawn with its material's base colour,
// unlit, over an empty background; and --verbose names the extensions that change nothing.
TEST(Material, LinesWithoutNormalsShowTheirBaseColourAndVerboseListsIgnoredExtensions) {
  context();
  // Vertices (−1, 0, 0), (1, 0, 0), (1, 0.5, 0) as a data URI, seen from +Z.
  const std::string json = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["KHR_materials_sheen"],
    "scene":0,"scenes":[{"nodes":[0,1]}],
    "nodes":[{"mesh":0},{"camera":0,"translation":[0,0.25,3]}],
    "cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],
    "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.25,0.5,0.75,1]},
                  "extensions":{"KHR_materials_sheen":{"sheenColorFactor":[1,1,1]}}}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":3,"material":0}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                  "min":[-1,0,0],"max":[1,0.5,0]}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AACAvwAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAAD8AAAAA"}]})";
  const std::string path = (testFolder() / "lines.gltf").string();
  std::ofstream(path) << json;
  RenderRequest r;
  r.width = 64;
  r.height = 48;
  r.ambient = glm::vec3(0.3f);
  const RenderOutcome out = renderScene(loadGltf(path), r);
  int covered = 0;
  for (int y = 0; y < r.height; ++y) {
    for (int x = 0; x < r.width; ++x) {
      const float* px = out.image.pixel(x, y);
      if (px[3] == 0.0f) continue;
      ++covered;
      EXPECT_FLOAT_EQ(px[0], 0.25f);
      EXPECT_FLOAT_EQ(px[1], 0.5f);
      EXPECT_FLOAT_EQ(px[2], 0.75f);
    }
  }
  // One pixel wide: about the strip's length in pixels (about 40 across, 10 up).
  EXPECT_GT(covered, 30);
  EXPECT_LT(covered, 150);
  const std::string png = (testFolder() / "lines.png").string();
  const ProcessResult cli = manylight("render " + path + " -o " + png + " --size 64x48 --verbose");
  EXPECT_EQ(cli.exitCode, 0) << cli.err;
  EXPECT_NE(
      cli.err.find(path + ": extensions ignored (they change nothing here): KHR_materials_sheen\n"),
      std::string::npos)
      << cli.err;
}

}  // namespace
}  // namespace manylight::testing
