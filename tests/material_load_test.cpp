// What the loader makes of glTF materials and the extensions real files require: every core
// texture with its UV set and KHR_texture_transform, alpha modes, emissive strength, unlit,
// points and lines, generated tangents, and the extensions refused by name.
#include <gtest/gtest.h>

#include <fstream>

#include "base/error.h"
#include "generators/scene_builder.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

BuilderTexture grey(int texCoord = 0) {
  BuilderTexture t;
  t.width = t.height = 2;
  t.rgba.assign(16, 128);
  t.texCoord = texCoord;
  return t;
}

std::string write(const std::string& name, const std::string& json) {
  const std::string path = (testFolder() / name).string();
  std::ofstream(path) << json;
  return path;
}

TEST(MaterialLoad, EveryCoreTextureKeepsItsSetItsTransformAndItsColourSpace) {
  BuilderMaterial m;
  m.textureWidth = m.textureHeight = 2;
  m.textureRgba.assign(16, 200);
  m.metallicRoughness = grey();
  m.normal = grey(1);
  m.normalScale = 0.5f;
  m.occlusion = grey();
  m.occlusionStrength = 0.25f;
  m.emissiveTexture = grey();
  m.emissiveTexture.transform = true;
  m.emissiveTexture.offset = {0.5f, 0.25f};
  m.emissiveTexture.scale = {2.0f, 3.0f};
  m.emissiveTexture.rotation = 1.5707963f;
  m.emissive = {1, 1, 1};
  m.emissiveStrength = 4.0f;
  m.alphaMode = "MASK";
  m.alphaCutoff = 0.3f;
  GltfBuilder b;
  b.addPlaneWithSecondUvs({0, 0, 0}, {1, 1}, b.addMaterial(m));
  const std::string path = (testFolder() / "all.gltf").string();
  b.write(path);
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& mat = s.materials[0];
  for (int k = 0; k < Material::kTextureSlots; ++k) EXPECT_GE(mat.slot(k).texture, 0) << k;
  EXPECT_TRUE(s.textures[mat.baseColorTexture.texture].srgb);
  EXPECT_TRUE(s.textures[mat.emissiveTexture.texture].srgb);
  EXPECT_FALSE(s.textures[mat.metallicRoughnessTexture.texture].srgb);
  EXPECT_FALSE(s.textures[mat.normalTexture.texture].srgb);
  EXPECT_FALSE(s.textures[mat.occlusionTexture.texture].srgb);
  EXPECT_EQ(mat.normalTexture.texCoord, 1);
  EXPECT_FLOAT_EQ(mat.normalScale, 0.5f);
  EXPECT_FLOAT_EQ(mat.occlusionStrength, 0.25f);
  EXPECT_FLOAT_EQ(mat.emissive.g, 4.0f);
  EXPECT_EQ(mat.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(mat.alphaCutoff, 0.3f);
  // KHR_texture_transform: uv' = T · R · S · uv, R's columns (cos, sin), (−sin, cos) as the
  // extension writes it. (1, 0) → scaled (2, 0) → rotated by 90° (0, 2) → offset (0.5, 2.25).
  const glm::vec3 moved = mat.emissiveTexture.transform * glm::vec3(1, 0, 1);
  EXPECT_NEAR(moved.x, 0.5f, 1e-5f);
  EXPECT_NEAR(moved.y, 2.25f, 1e-5f);
  const Primitive& p = s.meshes[0].primitives[0];
  EXPECT_EQ(p.texcoords1.size(), p.positions.size());
  // Tangents from the normal texture's UVs, TEXCOORD_1 = (1 − u, v): its u runs along −X on
  // the builder's plane, and glTF's bitangent cross(n, t) · w points up the image (−Z, v
  // running along +Z): cross(+Y, −X) = +Z, so w = −1 (a mirrored set).
  ASSERT_EQ(p.tangents.size(), p.positions.size());
  for (const glm::vec4& t : p.tangents) {
    EXPECT_NEAR(t.x, -1.0f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
    EXPECT_NEAR(t.z, 0.0f, 1e-6f);
    EXPECT_EQ(t.w, -1.0f);
  }
}

TEST(MaterialLoad, UnlitAndItsRequirementAreAccepted) {
  BuilderMaterial m;
  m.unlit = true;
  GltfBuilder b;
  b.addPlane({0, 0, 0}, {1, 1}, b.addMaterial(m));
  const std::string path = (testFolder() / "unlit.gltf").string();
  b.write(path);
  EXPECT_TRUE(loadGltf(path).materials[0].unlit);
}

// A triangle's three vertices drawn as each mode: points stay points, line strips and loops
// become segments.
TEST(MaterialLoad, PointsAndLinesKeepTheirMode) {
  // 3 vertices (x, y, z floats) as a data URI: (0,0,0), (1,0,0), (0,1,0).
  const std::string buffer =
      "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
  auto scene = [&](int mode) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":)" +
           std::to_string(mode) + R"(}]}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                    "min":[0,0,0],"max":[1,1,0]}],
      "bufferViews":[{"buffer":0,"byteLength":36}],
      "buffers":[{"byteLength":36,"uri":")" +
           buffer + R"("}]})";
  };
  struct Case {
    int mode;
    PrimitiveMode expected;
    std::vector<std::uint32_t> indices;
  };
  const Case cases[] = {{0, PrimitiveMode::Points, {0, 1, 2}},
                        {1, PrimitiveMode::Lines, {0, 1}},
                        {2, PrimitiveMode::Lines, {0, 1, 1, 2, 2, 0}},
                        {3, PrimitiveMode::Lines, {0, 1, 1, 2}},
                        {4, PrimitiveMode::Triangles, {0, 1, 2}}};
  for (const Case& c : cases) {
    const Scene s = loadGltf(write("mode" + std::to_string(c.mode) + ".gltf", scene(c.mode)));
    ASSERT_EQ(s.meshes.size(), 1u) << c.mode;
    const Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.mode, c.expected) << c.mode;
    EXPECT_EQ(p.indices, c.indices) << c.mode;
    EXPECT_EQ(p.normals.empty(), c.expected != PrimitiveMode::Triangles) << c.mode;
  }
}

TEST(MaterialLoad, BadMaterialsAndBasisuAreRefusedByName) {
  const std::string head = R"({"asset":{"version":"2.0"},)";
  struct Case {
    const char* name;
    std::string json, message;
  };
  const Case cases[] = {
      {"alpha", head + R"("materials":[{"alphaMode":"GLASS"}]})",
       "material 0: unknown alphaMode 'GLASS'"},
      {"basisu", head + R"("extensionsUsed":["KHR_texture_basisu"],
        "extensionsRequired":["KHR_texture_basisu"]})",
       "required extension KHR_texture_basisu is not supported: Basis Universal (KTX2) "
       "textures have no decoder here"},
      {"strength", head + R"("extensionsUsed":["KHR_materials_emissive_strength"],
        "materials":[{"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":-1}}}]})",
       "material 0: emissiveStrength must be a finite number >= 0"},
  };
  for (const Case& c : cases) {
    std::string json = c.json;
    // Materials are converted when a primitive uses them.
    if (json.find("materials") != std::string::npos) {
      json.insert(
          head.size(),
          R"("scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
        "bufferViews":[{"buffer":0,"byteLength":36}],
        "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)");
    }
    const std::string path = write(std::string(c.name) + ".gltf", json);
    try {
      loadGltf(path);
      ADD_FAILURE() << c.name << ": loaded";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()), path + ": " + c.message) << c.name;
    }
  }
}

}  // namespace
}  // namespace manylight::testing
