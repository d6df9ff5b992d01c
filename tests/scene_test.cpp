// glTF loading into scene/ types: spec defaults, transforms, lights, cameras, materials.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>

#include "base/error.h"
#include "scene/asset_files.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

std::string write(const std::string& name, const std::string& json) {
  const auto p = testFolder() / name;
  std::ofstream(p) << json;
  return p.string();
}

constexpr float kEps = 1e-5f;

void expectNear(glm::vec3 a, glm::vec3 b) {
  EXPECT_NEAR(a.x, b.x, kEps);
  EXPECT_NEAR(a.y, b.y, kEps);
  EXPECT_NEAR(a.z, b.z, kEps);
}

TEST(Scene, LightDefaultsFollowTheSpec) {
  const Scene s = loadGltf(write("defaults.gltf", R"({"asset": {"version": "2.0"},
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "point"}, {"type": "spot", "spot": {}}, {"type": "directional"}]}},
    "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}},
              {"extensions": {"KHR_lights_punctual": {"light": 1}}},
              {"extensions": {"KHR_lights_punctual": {"light": 2}}}],
    "scenes": [{"nodes": [0, 1, 2]}]})"));
  ASSERT_EQ(s.lights.size(), 3u);
  for (const Light& l : s.lights) {
    expectNear(l.colour, glm::vec3(1.0f));
    EXPECT_EQ(l.intensity, 1.0f);
    EXPECT_EQ(l.range, 0.0f);  // infinite
    expectNear(l.direction, {0.0f, 0.0f, -1.0f});
    expectNear(l.position, {0.0f, 0.0f, 0.0f});
  }
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_EQ(s.lights[1].type, LightType::Spot);
  EXPECT_NEAR(s.lights[1].innerConeAngle, 0.0f, kEps);
  EXPECT_NEAR(s.lights[1].outerConeAngle, float(M_PI / 4), kEps);
  EXPECT_EQ(s.lights[2].type, LightType::Directional);
}

TEST(Scene, LightsTakeTheirNodesWorldTransform) {
  // Parent: translate (1,2,3), rotate 90° about Y. Child: translate (0,0,-1) by matrix.
  // A light looking down −Z in the child frame looks down −X in the world.
  const Scene s = loadGltf(write("transforms.gltf", R"({"asset": {"version": "2.0"},
    "extensions": {"KHR_lights_punctual": {"lights": [
      {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 20, "range": 7,
       "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}}]}},
    "nodes": [{"translation": [1, 2, 3], "rotation": [0, 0.7071067811865476, 0, 0.7071067811865476],
               "children": [1]},
              {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,-1,1],
               "extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "scenes": [{"nodes": [0]}], "scene": 0})"));
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& l = s.lights[0];
  expectNear(l.position, {0.0f, 2.0f, 3.0f});
  expectNear(l.direction, {-1.0f, 0.0f, 0.0f});
  expectNear(l.colour, {1.0f, 0.5f, 0.25f});
  EXPECT_EQ(l.intensity, 20.0f);
  EXPECT_EQ(l.range, 7.0f);
  EXPECT_NEAR(l.innerConeAngle, 0.2f, kEps);
  EXPECT_NEAR(l.outerConeAngle, 0.4f, kEps);
}

TEST(Scene, CamerasPerspectiveAndOrthographic) {
  const Scene s = loadGltf(write("cameras.gltf", R"({"asset": {"version": "2.0"},
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}},
                {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 3, "znear": 0.5, "zfar": 50}}],
    "nodes": [{"camera": 0, "translation": [0, 1, 5], "scale": [2, 2, 2]}, {"camera": 1}],
    "scenes": [{"nodes": [0, 1]}]})"));
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_FALSE(s.cameras[0].orthographic);
  EXPECT_NEAR(s.cameras[0].yfov, 0.7f, kEps);
  EXPECT_EQ(s.cameras[0].zfar, 0.0f);  // infinite
  expectNear(glm::vec3(s.cameras[0].world[3]), {0.0f, 1.0f, 5.0f});
  expectNear(glm::vec3(s.cameras[0].world[0]), {1.0f, 0.0f, 0.0f});  // scale removed
  EXPECT_TRUE(s.cameras[1].orthographic);
  EXPECT_EQ(s.cameras[1].ymag, 3.0f);
  EXPECT_EQ(s.cameras[1].zfar, 50.0f);
}

TEST(Scene, MaterialsAndGeometry) {
  GltfBuilder b;
  BuilderMaterial m;
  m.baseColor = {0.5f, 0.25f, 1.0f, 1.0f};
  m.metallic = 0.3f;
  m.roughness = 0.6f;
  m.emissive = {0.1f, 0.2f, 0.3f};
  m.doubleSided = true;
  b.addBox({1.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, b.addMaterial(m));
  b.addSphere({0.0f, 0.0f, 0.0f}, 1.0f, b.addMaterial({}), 8);
  const std::string path = (testFolder() / "geometry.glb").string();
  b.write(path);
  const Scene s = loadGltf(path);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  EXPECT_NEAR(s.materials[0].metallic, 0.3f, kEps);
  EXPECT_NEAR(s.materials[0].roughness, 0.6f, kEps);
  expectNear(s.materials[0].emissive, {0.1f, 0.2f, 0.3f});
  EXPECT_TRUE(s.materials[0].doubleSided);
  ASSERT_EQ(s.instances.size(), 2u);
  const Primitive& box = s.meshes[s.instances[0].mesh].primitives[0];
  EXPECT_EQ(box.indices.size(), 36u);
  EXPECT_EQ(box.positions.size(), 24u);
  const Bounds bounds = s.bounds();
  expectNear(bounds.min, {-0.5f, -1.0f, -1.0f});
  expectNear(bounds.max, {2.0f, 1.0f, 1.0f});
}

TEST(Scene, DefaultMaterialIsPureLambert) {
  const Material m = defaultMaterial();
  EXPECT_EQ(m.metallic, 0.0f);
  EXPECT_EQ(m.roughness, 1.0f);
  EXPECT_EQ(m.baseColorFactor, glm::vec4(1.0f));
}

TEST(Scene, NoScenesShowsRootNodesAndUnknownTypesFail) {
  const Scene s = loadGltf(write("noscene.gltf", R"({"asset": {"version": "2.0"},
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}]}},
    "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}]})"));
  EXPECT_EQ(s.lights.size(), 1u);
  const std::string bad = write("badtype.gltf", R"({"asset": {"version": "2.0"},
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "area"}]}},
    "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}]})");
  try {
    loadGltf(bad);
    FAIL() << "expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), bad + ": light 0: unknown type 'area'");
  }
}

// The scene file is mapped, not copied: its bytes as written, zeros readable past its end
// for the parser's padding (also when it ends on a page boundary), and a buffer of its own
// once it grows past its capacity.
TEST(Scene, SceneFilesAreMappedWithZeroPadding) {
  namespace fs = std::filesystem;
  for (const std::size_t size : {std::size_t(0), std::size_t(5), std::size_t(4096)}) {
    const fs::path p = testFolder() / ("mapped-" + std::to_string(size) + ".gltf");
    std::ofstream(p, std::ios::binary) << std::string(size, 'a');
    AssetFiles files(p.string(), "", 1 << 20);
    FileBytes bytes;
    std::string err;
    ASSERT_TRUE(files.read(&bytes, &err, p.string(), 64)) << err;
    ASSERT_EQ(bytes.size(), size);
    ASSERT_GE(bytes.capacity(), size + 64);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()), size),
              std::string(size, 'a'));
    for (std::size_t i = size; i < size + 64; ++i)
      ASSERT_EQ(bytes.data()[i], 0) << size << " " << i;
    if (size == 0) continue;
    bytes.data()[0] = 'b';  // writable, copy-on-write: the file keeps its bytes
    bytes.resize(bytes.capacity() + 1);
    EXPECT_EQ(bytes.data()[0], 'b');
    EXPECT_EQ(bytes.size(), bytes.capacity());
  }
  std::ifstream f(testFolder() / "mapped-5.gltf");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(f), {}), "aaaaa");
}

}  // namespace
}  // namespace manylight::testing

namespace manylight::testing {
namespace {

TEST(Scene, AssetLinksOutOfTheFolderFifosAndOversizedFilesAreRefused) {
  namespace fs = std::filesystem;
  const fs::path outside = testFolder() / "outside.bin";
  std::ofstream(outside) << "12345678";
  const fs::path assets = testFolder() / "assets";
  fs::create_directories(assets);
  fs::create_symlink(outside, assets / "link.bin");
  ASSERT_EQ(::mkfifo((assets / "fifo.bin").c_str(), 0600), 0);
  std::ofstream(assets / "big.bin") << std::string(4096, 'x');
  auto scene = [&](const std::string& uri, int bytes = 8) {
    const fs::path p = assets / "s.gltf";
    std::ofstream(p) << R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" << uri
                     << R"(", "byteLength": )" << bytes << "}]}";
    return p.string();
  };
  const std::string s = scene("link.bin");
  EXPECT_EQ(loadError(s),
            s + ": URI 'link.bin': leads outside the scene's folder (through a link)");
  EXPECT_EQ(loadError(scene("fifo.bin")),
            s + ": URI 'fifo.bin': not a regular file");  // would block
  LoadOptions small;
  small.maxFileBytes = 1024;
  EXPECT_EQ(loadError(scene("big.bin", 4096), small),
            s + ": the scene's files exceed the limit of 1024 bytes");
  EXPECT_EQ(loadError(scene("big.bin", 4096)), "");
  EXPECT_EQ(loadError(scene("sub/../big.bin", 4096)), "") << "a path that stays inside is fine";
}

}  // namespace
}  // namespace manylight::testing

namespace manylight::testing {
namespace {

// An image whose bytes start as a PNG or JPEG does and then go wrong is refused with its
// decoder's exact message, and other bytes before any decoder sees them. (That OpenImageIO
// tries no other reader on them is not visible here: the other readers refuse such bytes
// with the same message.)
TEST(Scene, CorruptPngAndJpegImagesAreRefusedWithTheirDecodersMessage) {
  namespace fs = std::filesystem;
  const fs::path dir = testFolder() / "images";
  fs::create_directories(dir);
  auto scene = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    const fs::path p = dir / (name + ".gltf");
    std::ofstream(p) << R"({"asset": {"version": "2.0"}, "images": [{"uri": ")" << name
                     << R"("}]})";
    return p.string();
  };
  const std::string garbage(100, 'A');
  const std::string png = scene("bad.png", std::string("\x89PNG\r\n\x1a\n", 8) + garbage);
  const std::string jpeg = scene("bad.jpg", "\xFF\xD8\xFF" + garbage);
  const std::string dds = scene("bad.dds", "DDS " + garbage);
  const std::string prefix = ": image 0: cannot decode image: ";
  EXPECT_EQ(loadError(png), png + prefix +
                                "Read error: hit end of file PNG read error: AAAA: Read error: "
                                "hit end of file");
  EXPECT_EQ(loadError(jpeg),
            jpeg + prefix + "JPEG error: Unsupported marker type 0x41 (\"image.jpg\")");
  EXPECT_EQ(loadError(dds), dds + ": image 0: not a PNG or JPEG image");
}

// A GLB image whose bufferView runs past its buffer's byteLength (though not past the file's
// binary chunk) is refused before any decoder reads it: tinygltf hands such bytes over
// unchecked, and the PNG reader read beyond the buffer (libFuzzer found it; this test runs
// under AddressSanitizer in CI).
TEST(Scene, AnImageViewPastItsBufferIsRefusedBeforeDecoding) {
  std::string bin = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16) + std::string(48, '\0');
  std::string json =
      R"({"asset": {"version": "2.0"}, "images": [{"bufferView": 0, "mimeType": "image/png"}],)"
      R"( "bufferViews": [{"buffer": 0, "byteLength": 64}], "buffers": [{"byteLength": 16}]})";
  json.resize((json.size() + 3) / 4 * 4, ' ');
  auto word = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const std::string glb = "glTF" + word(2) + word(std::uint32_t(28 + json.size() + bin.size())) +
                          word(std::uint32_t(json.size())) + "JSON" + json +
                          word(std::uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  const std::string path = (testFolder() / "past.glb").string();
  std::ofstream(path, std::ios::binary) << glb;
  EXPECT_EQ(loadError(path),
            path + ": image 0: bufferView 0: bytes 0..64 lie beyond its buffer's 16");
}

}  // namespace
}  // namespace manylight::testing
