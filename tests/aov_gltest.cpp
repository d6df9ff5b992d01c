// render --aov: each material channel of a plane with known factors and textures, as exact
// values in the Image of renderScene and exact codes in the PNG the program writes.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "generators/scene_builder.h"
#include "image/image.h"
#include "render/aov.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "scene/srgb.h"
#include "tests/cli_support.h"
#include "tests/gl_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

constexpr int kSize = 16;

// An 8×8 texture of texel `a`, or a checker of `a` and `b` in 2×2 blocks; nearest filtering,
// so every pixel reads one texel exactly.
BuilderTexture texture(glm::u8vec4 a, glm::u8vec4 b) {
  BuilderTexture t;
  t.width = t.height = 8;
  t.nearest = true;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const glm::u8vec4 c = ((x / 2) + (y / 2)) % 2 ? b : a;
      t.rgba.insert(t.rgba.end(), {c.r, c.g, c.b, c.a});
    }
  }
  return t;
}
BuilderTexture texture(glm::u8vec4 a) { return texture(a, a); }

// A 2×2 plane facing +Y carrying `m`, filling the view of a camera above it, with a light
// (which no AOV reads). Returns the .gltf's path.
std::string planeScene(const std::string& name, const BuilderMaterial& m) {
  GltfBuilder b;
  b.addPlane({0, 0, 0}, {2, 2}, b.addMaterial(m));
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0, -1, 0};
  sun.intensity = 3.0f;
  b.addLight(sun);
  b.addPerspectiveCamera({0, 2, 0.01f}, {0, 0, 0}, 0.6f);
  const std::string path = (testFolder() / (name + ".gltf")).string();
  b.write(path);
  return path;
}

Image renderAov(const std::string& path, Aov aov, Method method = Method::Reference) {
  RenderRequest r;
  r.width = r.height = kSize;
  r.method = method;
  r.ambient = glm::vec3(0.2f);  // read by no AOV
  r.aov = aov;
  return renderScene(loadGltf(path), r).image;
}

// Every pixel of `image` holds `rgb` within `tolerance` per channel, and coverage 1.
void expectEveryPixel(const Image& image, glm::vec3 rgb, float tolerance) {
  ASSERT_EQ(image.width * image.height, kSize * kSize);
  int off = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      const bool same = std::abs(p[0] - rgb.r) <= tolerance &&
                        std::abs(p[1] - rgb.g) <= tolerance &&
                        std::abs(p[2] - rgb.b) <= tolerance && p[3] == 1.0f;
      if (!same && off++ < 3) {
        ADD_FAILURE() << "pixel " << x << "," << y << ": " << p[0] << " " << p[1] << " " << p[2]
                      << " " << p[3] << ", expected " << rgb.r << " " << rgb.g << " " << rgb.b;
      }
    }
  }
  EXPECT_EQ(off, 0) << "pixels off";
}

// Every pixel of the 8-bit file `path` holds the codes `rgb` within `tolerance`, and alpha 255.
void expectEveryCode(const std::string& path, glm::ivec3 rgb, int tolerance = 0) {
  const Image png = readImage(path);
  ASSERT_EQ(png.width * png.height, kSize * kSize) << path;
  int off = 0;
  for (std::size_t i = 0; i < png.rgba.size(); ++i) {
    const int expected = i % 4 == 3 ? 255 : rgb[int(i % 4)];
    if (std::abs(std::lround(png.rgba[i] * 255.0f) - expected) > tolerance && off++ < 3) {
      ADD_FAILURE() << path << ": value " << i << " is code " << png.rgba[i] * 255.0f
                    << ", expected " << expected;
    }
  }
  EXPECT_EQ(off, 0) << "values off";
}

// The code of a data value, as the PNG writer rounds it.
int dataCode(float v) { return int(std::lround(v * 255.0f)); }

// Values differ from the float arithmetic here by the GPU's rounding (and the interpolated
// vertex colour's, which is not exactly 1 everywhere): 1e-5.
constexpr float kExact = 1e-5f;
// Colour textures are decoded at upload into 16-bit float texels: a value below 1 is off by at
// most half a unit in their last place, under 5e-4; so its sRGB code may be one off.
constexpr float kHalfFloat = 5e-4f;
constexpr int kHalfFloatCodes = 1;

TEST(Aov, EveryVariantCompilesAndLinks) {
  context();
  for (const AovChannel& c : kAovChannels) {
    EXPECT_NO_THROW(gl::Program("gbuffer.vert", "gbuffer.frag", aovDefines(c.aov), {"gRadiance"}))
        << c.name;
  }
  EXPECT_TRUE(aovDefines(Aov::None).empty());
}

TEST(Aov, BaseColourIsFactorTimesTextureInLinear) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.8f, 0.5f, 0.25f, 1.0f};
  const BuilderTexture t = texture({200, 100, 255, 255});
  m.textureWidth = t.width;
  m.textureHeight = t.height;
  m.textureRgba = t.rgba;
  m.textureNearest = true;
  m.metallic = 1.0f;  // base colour is the same for metals
  const std::string path = planeScene("base", m);
  const glm::vec3 linear = glm::vec3(0.8f, 0.5f, 0.25f) *
                           glm::vec3(decodeSrgb8(200), decodeSrgb8(100), decodeSrgb8(255));
  const Image image = renderAov(path, Aov::BaseColour);
  EXPECT_EQ(image.values, ImageValues::Colour);
  expectEveryPixel(image, linear, kHalfFloat);
  const std::string png = (testFolder() / "base.png").string();
  ASSERT_EQ(manylight("render " + path + " -o " + png + " --size 16x16 --aov base-colour").exitCode,
            0);
  expectEveryCode(png, {encodeSrgb8(linear.r), encodeSrgb8(linear.g), encodeSrgb8(linear.b)},
                  kHalfFloatCodes);
}

TEST(Aov, MetallicAndRoughnessAreFactorsTimesTheTexturesBAndG) {
  context();
  BuilderMaterial m;
  m.metallic = 0.6f;
  m.roughness = 0.9f;
  m.metallicRoughness = texture({0, 130, 210, 255});
  const std::string path = planeScene("mr", m);
  const float metallic = 0.6f * 210 / 255.0f, roughness = 0.9f * 130 / 255.0f;
  const Image mImage = renderAov(path, Aov::Metallic);
  EXPECT_EQ(mImage.values, ImageValues::Data);
  expectEveryPixel(mImage, glm::vec3(metallic), kExact);
  expectEveryPixel(renderAov(path, Aov::Roughness), glm::vec3(roughness), kExact);
  // The lightcuts methods give the same channel: an AOV lights nothing.
  expectEveryPixel(renderAov(path, Aov::Roughness, Method::Lightcuts), glm::vec3(roughness),
                   kExact);
  const fs::path dir = testFolder();
  // 255 · value, not sRGB-encoded; --exposure does not scale an AOV.
  ASSERT_EQ(manylight("render " + path + " -o " + (dir / "m.png").string() +
                      " --size 16x16 --aov metallic --exposure 2")
                .exitCode,
            0);
  expectEveryCode((dir / "m.png").string(), glm::ivec3(dataCode(metallic)));
  ASSERT_EQ(manylight("render " + path + " -o " + (dir / "r.png").string() +
                      " --size 16x16 --aov roughness --method lightcuts")
                .exitCode,
            0);
  expectEveryCode((dir / "r.png").string(), glm::ivec3(dataCode(roughness)));
}

TEST(Aov, OcclusionIsTheTexelsRWithoutStrength) {
  context();
  BuilderMaterial m;
  m.occlusion = texture({90, 0, 0, 255});
  m.occlusionStrength = 0.5f;
  const std::string path = planeScene("occlusion", m);
  expectEveryPixel(renderAov(path, Aov::Occlusion), glm::vec3(90 / 255.0f), kExact);
  const std::string png = (testFolder() / "occlusion.png").string();
  ASSERT_EQ(manylight("render " + path + " -o " + png + " --size 16x16 --aov occlusion").exitCode,
            0);
  expectEveryCode(png, glm::ivec3(90));
  // Without an occlusion texture nothing is occluded.
  expectEveryPixel(renderAov(planeScene("plain", {}), Aov::Occlusion), glm::vec3(1.0f), 0.0f);
}

TEST(Aov, EmissiveIsFactorTimesStrengthTimesTexture) {
  context();
  BuilderMaterial m;
  m.emissive = {1.0f, 0.5f, 0.25f};
  m.emissiveStrength = 0.8f;
  m.emissiveTexture = texture({255, 180, 60, 255});
  const std::string path = planeScene("emissive", m);
  const glm::vec3 linear = glm::vec3(1.0f, 0.5f, 0.25f) * 0.8f *
                           glm::vec3(decodeSrgb8(255), decodeSrgb8(180), decodeSrgb8(60));
  const Image image = renderAov(path, Aov::Emissive);
  EXPECT_EQ(image.values, ImageValues::Colour);
  expectEveryPixel(image, linear, kHalfFloat);
  const std::string png = (testFolder() / "emissive.png").string();
  ASSERT_EQ(manylight("render " + path + " -o " + png + " --size 16x16 --aov emissive").exitCode,
            0);
  expectEveryCode(png, {encodeSrgb8(linear.r), encodeSrgb8(linear.g), encodeSrgb8(linear.b)},
                  kHalfFloatCodes);
}

TEST(Aov, NormalIsTheWorldSpaceShadingNormalHalvedAndShifted) {
  context();
  // No normal texture: the plane's +Y.
  expectEveryPixel(renderAov(planeScene("flat", {}), Aov::Normal), {0.5f, 1.0f, 0.5f}, kExact);
  // A normal texture tilted towards +u: the builder's plane has u along +X, the bitangent
  // (the image's top) along −Z, the normal +Y.
  BuilderMaterial m;
  const glm::u8vec4 texel{204, 128, 230, 255};
  m.normal = texture(texel);
  const std::string path = planeScene("tilted", m);
  const glm::vec3 tangentSpace = glm::normalize(glm::vec3(texel) / 255.0f * 2.0f - 1.0f);
  const glm::vec3 world(tangentSpace.x, tangentSpace.z, -tangentSpace.y);
  const glm::vec3 encoded = world * 0.5f + 0.5f;
  const Image image = renderAov(path, Aov::Normal);
  EXPECT_EQ(image.values, ImageValues::Data);
  expectEveryPixel(image, encoded, 1e-4f);
  const fs::path dir = testFolder();
  ASSERT_EQ(
      manylight("render " + path + " -o " + (dir / "n.png").string() + " --size 16x16 --aov normal")
          .exitCode,
      0);
  expectEveryCode((dir / "n.png").string(),
                  {dataCode(encoded.x), dataCode(encoded.y), dataCode(encoded.z)});
  // EXR holds (n + 1) / 2 as it is.
  ASSERT_EQ(
      manylight("render " + path + " -o " + (dir / "n.exr").string() + " --size 16x16 --aov normal")
          .exitCode,
      0);
  expectEveryPixel(readImage((dir / "n.exr").string()), encoded, 1e-4f);
}

TEST(Aov, AlphaIsBaseAlphaOutsideOpaqueAndMaskDiscards) {
  context();
  BuilderMaterial m;
  m.baseColor = {1.0f, 1.0f, 1.0f, 0.4f};
  m.alphaMode = "BLEND";
  expectEveryPixel(renderAov(planeScene("blend", m), Aov::Alpha), glm::vec3(0.4f), kExact);
  m.alphaMode = "OPAQUE";  // glTF ignores alpha here
  expectEveryPixel(renderAov(planeScene("opaque", m), Aov::Alpha), glm::vec3(1.0f), 0.0f);
  // MASK: a checker of alpha 0.8 and 0.2 (texture alpha is linear) against cutoff 0.5.
  m.baseColor = glm::vec4(1.0f);
  m.alphaMode = "MASK";
  const BuilderTexture t = texture({255, 255, 255, 204}, {255, 255, 255, 51});
  m.textureWidth = t.width;
  m.textureHeight = t.height;
  m.textureRgba = t.rgba;
  m.textureNearest = true;
  const std::string path = planeScene("mask", m);
  const std::string png = (testFolder() / "mask.png").string();
  ASSERT_EQ(manylight("render " + path + " -o " + png + " --size 16x16 --aov alpha").exitCode, 0);
  const Image codes = readImage(png);
  int kept = 0, discarded = 0;
  for (int i = 0; i < kSize * kSize; ++i) {
    const float* p = &codes.rgba[std::size_t(i) * 4];
    if (p[3] == 0.0f && p[0] == 0.0f) {
      ++discarded;
    } else {
      EXPECT_EQ(std::lround(p[0] * 255.0f), 204) << "pixel " << i;
      EXPECT_EQ(p[3], 1.0f) << "pixel " << i;
      ++kept;
    }
  }
  EXPECT_GT(kept, 0);
  EXPECT_GT(discarded, 0);
}

TEST(Aov, UnlitSurfacesHaveOnlyBaseColourAndAlpha) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.25f, 0.5f, 0.75f, 1.0f};
  m.emissive = glm::vec3(1.0f);
  m.unlit = true;
  const std::string path = planeScene("unlit", m);
  expectEveryPixel(renderAov(path, Aov::BaseColour), {0.25f, 0.5f, 0.75f}, kExact);
  expectEveryPixel(renderAov(path, Aov::Alpha), glm::vec3(1.0f), 0.0f);
  for (const Aov aov :
       {Aov::Metallic, Aov::Roughness, Aov::Normal, Aov::Emissive, Aov::Occlusion}) {
    const Image image = renderAov(path, aov);
    for (const float v : image.rgba) ASSERT_EQ(v, 0.0f) << aovChannel(aov).name << " covered";
  }
}

// The renderer keeps its lit program: an AOV frame between two lit ones changes neither.
TEST(Aov, LitFramesAroundAnAovFrameAreTheSame) {
  context();
  BuilderMaterial m;
  m.baseColor = {0.7f, 0.6f, 0.5f, 1.0f};
  m.roughness = 0.4f;
  const Scene scene = loadGltf(planeScene("lit", m));
  Renderer renderer(scene, scene.lights, kSize, kSize, Method::Reference);
  const View view = makeView(scene.cameras[0], kSize, kSize);
  FrameSettings lit;
  lit.ambient = glm::vec3(0.1f);
  FrameSettings aov = lit;
  aov.aov = Aov::Roughness;
  const Image before = renderer.render(view, lit);
  FrameStats stats;
  const Image channel = renderer.render(view, aov, &stats);
  EXPECT_EQ(stats.lightingPasses, 0);
  expectEveryPixel(channel, glm::vec3(0.4f), kExact);
  const Image after = renderer.render(view, lit);
  EXPECT_EQ(before.values, ImageValues::Colour);
  EXPECT_EQ(before.rgba, after.rgba);
  EXPECT_NE(before.rgba, channel.rgba);
}

TEST(Aov, CliRecordsItInStatsTakesItInBatchesAndRefusesUnknownNames) {
  BuilderMaterial m;
  m.roughness = 0.3f;
  const std::string path = planeScene("cli", m);
  const fs::path dir = testFolder();
  ASSERT_EQ(manylight("render " + path + " -o " + (dir / "a.png").string() +
                      " --size 16x16 --aov roughness --stats " + (dir / "stats.json").string())
                .exitCode,
            0);
  const auto stats = nlohmann::json::parse(readFile(dir / "stats.json"));
  EXPECT_EQ(stats["aov"], "roughness");
  EXPECT_EQ(stats["lighting_passes"], 0);
  const ProcessResult lit = manylight("render " + path + " -o " + (dir / "b.png").string() +
                                      " --size 16x16 --stats " + (dir / "lit.json").string());
  ASSERT_EQ(lit.exitCode, 0) << lit.err;
  EXPECT_FALSE(nlohmann::json::parse(readFile(dir / "lit.json")).contains("aov"));
  const ProcessResult batch = manylight("render " + path + " --out-dir " +
                                        (dir / "batch").string() + " --size 16x16 --aov roughness");
  ASSERT_EQ(batch.exitCode, 0) << batch.err;
  expectEveryCode((dir / "batch" / "cli.png").string(), glm::ivec3(dataCode(0.3f)));
  const ProcessResult bad = manylight("render " + path + " -o x.png --aov albedo");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--aov"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("albedo"), std::string::npos) << bad.err;
}

TEST(Aov, ParseAovNamesEveryChoice) {
  EXPECT_EQ(parseAov(""), Aov::None);
  EXPECT_EQ(parseAov("base-colour"), Aov::BaseColour);
  EXPECT_EQ(parseAov("alpha"), Aov::Alpha);
  try {
    parseAov("albedo");
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown AOV 'albedo', expected one of base-colour, metallic, roughness, normal, "
                 "emissive, occlusion, alpha");
  }
  EXPECT_EQ(aovNames().size(), std::size(kAovChannels));
}

}  // namespace
}  // namespace manylight::testing
