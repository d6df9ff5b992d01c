// Compressed geometry (KHR_draco_mesh_compression, EXT_meshopt_compression) loads as the
// same mesh uncompressed, and bad compressed data is refused with one exact line.
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "base/error.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_meshopt.h"
#include "tests/compressed_scenes.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

std::string writeFile(const std::string& name, const GltfFile& f) {
  const std::string path = (testFolder() / name).string();
  writeGltf(path, f);
  return path;
}

const Primitive& onlyPrimitive(const Scene& s) {
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes.at(0).primitives.size(), 1u);
  return s.meshes.at(0).primitives.at(0);
}

bool near(const glm::vec3& a, const glm::vec3& b, float tol) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)));
}

// Every triangle of `a` is a triangle of `b` (the same corners in the same winding, from any
// first corner; Draco's edgebreaker reorders vertices and triangles): positions within
// `tol`, normals within `normalTol`, texture coordinates within `uvTol`.
void expectSameTriangles(const Primitive& a, const Primitive& b, float tol, float normalTol,
                         float uvTol) {
  ASSERT_EQ(a.indices.size(), b.indices.size());
  ASSERT_EQ(a.normals.size(), a.positions.size());
  ASSERT_EQ(b.texcoords.size(), b.positions.size());
  std::vector<bool> used(b.indices.size() / 3, false);
  auto corner = [](const Primitive& p, std::size_t t, int k) { return p.indices[t * 3 + k % 3]; };
  for (std::size_t t = 0; t < a.indices.size() / 3; ++t) {
    bool found = false;
    for (std::size_t u = 0; u < used.size() && !found; ++u) {
      for (int r = 0; r < 3 && !used[u] && !found; ++r) {
        bool same = true;
        for (int k = 0; k < 3 && same; ++k) {
          const std::uint32_t i = corner(a, t, k), j = corner(b, u, k + r);
          same = near(a.positions[i], b.positions[j], tol) &&
                 near(a.normals[i], b.normals[j], normalTol) &&
                 near(glm::vec3(a.texcoords[i], 0), glm::vec3(b.texcoords[j], 0), uvTol);
        }
        if (same) used[u] = found = true;
      }
    }
    ASSERT_TRUE(found) << "triangle " << t << " has no match";
  }
}

// Draco's quantisation of the test meshes: positions 14 bits over an extent of 2 (one step
// 1.2e-4; rounding gives half of that), normals 10 bits octahedral (a step about 2e-3
// radians), texture coordinates 12 bits over 1 (2.4e-4). Each tolerance is one step.
constexpr float kDracoPosition = 2.0f / 16383, kDracoNormal = 4e-3f, kDracoUv = 1.0f / 4095;

TEST(Compression, DracoAGeneratedPrimitiveLoadsAsThePlainOne) {
  const TestMesh mesh = gridMesh(12);
  const Scene plain = loadGltf(writeFile("plain.glb", plainMeshFile(mesh)));
  for (const bool edgebreaker : {true, false}) {
    SCOPED_TRACE(edgebreaker ? "edgebreaker" : "sequential");
    const Scene draco = loadGltf(writeFile("draco.gltf", dracoMeshFile(mesh, edgebreaker)));
    expectSameTriangles(onlyPrimitive(plain), onlyPrimitive(draco), kDracoPosition, kDracoNormal,
                        kDracoUv);
    EXPECT_EQ(onlyPrimitive(draco).positions.size(), mesh.vertices());
  }
}

// The glTF sample Box, plain and Draco (positions quantised to 11 bits over its extent of 1:
// the Draco box's corners are at ±0.50049 instead of ±0.5).
TEST(Compression, DracoTheSampleBoxLoadsAsThePlainBox) {
  const fs::path shared = MANYLIGHT_SHARED_SCENES;
  if (!fs::exists(shared / "Box/glTF-Draco/Box.gltf")) GTEST_SKIP() << "no " << shared;
  const Scene plain = loadGltf((shared / "Box/glTF/Box.gltf").string());
  const Scene draco = loadGltf((shared / "Box/glTF-Draco/Box.gltf").string());
  const Primitive& a = onlyPrimitive(plain);
  const Primitive& b = onlyPrimitive(draco);
  EXPECT_EQ(b.indices.size(), 36u);
  EXPECT_EQ(b.positions.size(), 24u);
  Primitive a2 = a, b2 = b;
  a2.texcoords.assign(a.positions.size(), glm::vec2(0));
  b2.texcoords.assign(b.positions.size(), glm::vec2(0));
  expectSameTriangles(a2, b2, 1e-3f, 1e-3f, 0.0f);
  EXPECT_EQ(plain.instances.at(0).world, draco.instances.at(0).world);
}

struct BadInput {
  const char* name;
  std::function<void(GltfFile&)> change;
  std::string message;  // after "PATH: "
  std::int64_t maxTriangles = std::int64_t(1) << 26;
};

// The Draco grid of 2×2 quads, edgebreaker: 8 triangles, 9 vertices; accessor 0 is the
// indices, 1 POSITION, bufferView 0 the bitstream: bytes 5 and 6 its version, 13 the varint
// of its triangle count.
// Makes the bitstream of the grid below declare 2^28 triangles (a varint of five bytes).
void claimTriangles(GltfFile& f) {
  ASSERT_EQ(f.bin[13], 8);
  f.bin = f.bin.substr(0, 13) + std::string("\x80\x80\x80\x80\x01", 5) + f.bin.substr(14);
  f.json["bufferViews"][0]["byteLength"] = f.json["bufferViews"][0]["byteLength"].get<int>() + 4;
}

TEST(Compression, DracoBadInputsAreRefusedWithOneExactLine) {
  const std::string where = "mesh 0 primitive 0: KHR_draco_mesh_compression: ";
  const BadInput cases[] = {
      {"corrupt magic", [](GltfFile& f) { f.bin[0] = 'X'; },
       where + "not a Draco bitstream (Not a Draco file.)"},
      {"other version", [](GltfFile& f) { f.bin[6] = 1; },
       where + "Draco bitstream version 2.1 is not supported, expected 2.2"},
      {"truncated", [](GltfFile& f) { f.json["bufferViews"][0]["byteLength"] = 24; },
       where + "cannot decode: Failed to decode geometry data."},
      {"corrupt body",
       [](GltfFile& f) {
         for (std::size_t i = 20; i < f.bin.size(); ++i) f.bin[i] = char(0xA5);
       },
       where + "cannot decode: Failed to decode geometry data."},
      {"a bitstream claiming 2^28 triangles", [](GltfFile& f) { claimTriangles(f); },
       where + "the Draco data declares 268435456 triangles, accessor 0 (indices) has count 24"},
      {"and its accessor too",
       [](GltfFile& f) {
         claimTriangles(f);
         f.json["accessors"][0]["count"] = 3 << 28;
       },
       "268435456 triangles exceed the limit of 67108864"},
      {"indices count", [](GltfFile& f) { f.json["accessors"][0]["count"] = 21; },
       where + "the Draco data declares 8 triangles, accessor 0 (indices) has count 21"},
      {"position count", [](GltfFile& f) { f.json["accessors"][1]["count"] = 10; },
       where + "accessor 2 (NORMAL) has count 9, POSITION 10"},
      {"more vertices than indices",
       [](GltfFile& f) {
         for (int a : {1, 2, 3}) f.json["accessors"][a]["count"] = 25;
       },
       where + "accessor 1 (POSITION) has count 25, more than the 24 indices"},
      {"over --max-triangles", [](GltfFile&) {}, "8 triangles exceed the limit of 7", 7},
      {"strip", [](GltfFile& f) { f.primitive()["mode"] = 5; },
       where + "mode 5 is not TRIANGLES (4)"},
      {"no bufferView",
       [](GltfFile& f) {
         f.primitive()["extensions"]["KHR_draco_mesh_compression"].erase("bufferView");
       },
       where + "bufferView is missing or not an index"},
      {"unknown attribute",
       [](GltfFile& f) {
         f.primitive()["extensions"]["KHR_draco_mesh_compression"]["attributes"]["COLOR_0"] = 5;
       },
       where + "attribute COLOR_0 is not among the primitive's attributes"},
      {"wrong Draco id",
       [](GltfFile& f) {
         f.primitive()["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 9;
       },
       where + "attribute NORMAL: Draco attribute 9 does not exist"},
  };
  const TestMesh mesh = gridMesh(2);
  for (const BadInput& c : cases) {
    SCOPED_TRACE(c.name);
    GltfFile f = dracoMeshFile(mesh, true);
    ASSERT_EQ(f.json["accessors"][0]["count"], 24);
    ASSERT_EQ(f.json["accessors"][1]["count"], 9);
    c.change(f);
    const std::string path = writeFile("bad.glb", f);
    LoadOptions options;
    options.maxTriangles = c.maxTriangles;
    EXPECT_EQ(loadError(path, options), path + ": " + c.message);
  }
}

TEST(Compression, MeshoptViewsLoadIdenticallyToThePlainFile) {
  const TestMesh mesh = gridMesh(12);
  const Scene plain = loadGltf(writeFile("plain.glb", plainMeshFile(mesh)));
  const Primitive& a = onlyPrimitive(plain);
  for (const char* name : {"meshopt.glb", "meshopt.gltf"}) {
    for (const bool sequence : {false, true}) {
      SCOPED_TRACE(std::string(name) + (sequence ? " INDICES" : " TRIANGLES"));
      const Scene s = loadGltf(writeFile(name, meshoptMeshFile(mesh, false, sequence)));
      const Primitive& b = onlyPrimitive(s);
      EXPECT_EQ(a.positions, b.positions);
      EXPECT_EQ(a.normals, b.normals);
      EXPECT_EQ(a.texcoords, b.texcoords);
      EXPECT_EQ(a.indices, b.indices);
    }
  }
}

// Filters trade precision for size: 8-bit octahedral normals are within 1/127 per
// component after renormalisation (two steps: 2/127); exponential texture coordinates with a
// 15-bit signed mantissa (14 bits of magnitude) under an exponent shared by the vector's
// components, so scaled to its larger one (at most 1), are within 2^-14.
TEST(Compression, MeshoptFilteredViewsLoadWithinTheirPrecision) {
  const TestMesh mesh = gridMesh(12);
  const Primitive a = onlyPrimitive(loadGltf(writeFile("plain.glb", plainMeshFile(mesh))));
  const Scene s = loadGltf(writeFile("filters.glb", meshoptMeshFile(mesh, true, false)));
  const Primitive& b = onlyPrimitive(s);
  ASSERT_EQ(a.normals.size(), b.normals.size());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.indices, b.indices);
  for (std::size_t i = 0; i < a.normals.size(); ++i) {
    EXPECT_TRUE(near(a.normals[i], b.normals[i], 2.0f / 127)) << i;
    EXPECT_TRUE(near(glm::vec3(a.texcoords[i], 0), glm::vec3(b.texcoords[i], 0), 1.0f / 16384))
        << i;
  }
}

// The QUATERNION filter (animation rotations), on a model built here: 12-bit components
// decode to within 2^-11 of the unit quaternion, stored as 16-bit normalised integers.
TEST(Compression, MeshoptQuaternionViewsDecodeWithinTheirPrecision) {
  std::vector<float> q;
  for (int i = 0; i < 20; ++i) {
    const float angle = 0.3f * i, s = std::sin(angle / 2);
    const glm::vec3 axis = glm::normalize(glm::vec3(1, i % 3, 2));
    q.insert(q.end(), {axis.x * s, axis.y * s, axis.z * s, std::cos(angle / 2)});
  }
  std::vector<std::int16_t> filtered(q.size());
  meshopt_encodeFilterQuat(filtered.data(), 20, 8, 12, q.data());
  std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(20, 8));
  encoded.resize(
      meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), filtered.data(), 20, 8));
  tinygltf::Model model;
  model.buffers.resize(2);
  model.buffers[0].data = encoded;
  model.buffers[1].data = {0};  // a placeholder
  tinygltf::BufferView view;
  view.buffer = 1;
  view.byteLength = 160;
  tinygltf::Value::Object ext;
  ext["buffer"] = tinygltf::Value(0);
  ext["byteLength"] = tinygltf::Value(int(encoded.size()));
  ext["byteStride"] = tinygltf::Value(8);
  ext["count"] = tinygltf::Value(20);
  ext["mode"] = tinygltf::Value(std::string("ATTRIBUTES"));
  ext["filter"] = tinygltf::Value(std::string("QUATERNION"));
  view.extensions["EXT_meshopt_compression"] = tinygltf::Value(ext);
  model.bufferViews.push_back(view);
  gltf::decodeMeshoptViews(model, {1}, 1 << 20);
  const tinygltf::BufferView& v = model.bufferViews[0];
  ASSERT_EQ(v.buffer, 2);
  EXPECT_TRUE(model.buffers[1].data.empty());
  const auto* out =
      reinterpret_cast<const std::int16_t*>(model.buffers[2].data.data() + v.byteOffset);
  for (std::size_t i = 0; i < q.size(); i += 4) {
    // q and −q are the same rotation; the filter may return either.
    const float sign = (out[i + 3] < 0) == (q[i + 3] < 0) ? 1.0f : -1.0f;
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(sign * out[i + c] / 32767.0f, q[i + c], 1.0f / 2048);
  }
}

// The meshopt grid of 2×2 quads: 9 vertices, 24 indices; views 0 positions (108 bytes), 1
// normals, 2 texcoords, 3 indices; accessor 3 the indices; buffer 1 the placeholder.
TEST(Compression, MeshoptBadInputsAreRefusedWithOneExactLine) {
  auto ext = [](GltfFile& f, int view) -> nlohmann::json& {
    return f.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
  };
  const std::string view0 = "bufferView 0: EXT_meshopt_compression: ";
  const BadInput cases[] = {
      {"truncated", [&](GltfFile& f) { ext(f, 0)["byteLength"] = 20; },
       view0 + "the ATTRIBUTES data cannot be decoded (meshoptimizer error -2)"},
      {"corrupt", [&](GltfFile& f) { f.bin[0] = 0; },
       view0 + "the ATTRIBUTES data cannot be decoded (meshoptimizer error -1)"},
      {"count", [&](GltfFile& f) { ext(f, 0)["count"] = 10; },
       view0 + "count 10 times byteStride 12 is not the bufferView's byteLength 108"},
      {"stride", [&](GltfFile& f) { ext(f, 0)["byteStride"] = 16; },
       view0 + "byteStride 16 differs from the bufferView's 12"},
      {"mode", [&](GltfFile& f) { ext(f, 0)["mode"] = "POINTS"; }, view0 + "unknown mode 'POINTS'"},
      {"index filter", [&](GltfFile& f) { ext(f, 3)["filter"] = "OCTAHEDRAL"; },
       "bufferView 3: EXT_meshopt_compression: TRIANGLES takes no filter, got OCTAHEDRAL"},
      {"past its buffer", [&](GltfFile& f) { ext(f, 0)["byteOffset"] = 100000; },
       view0 + "bytes 100000..100125 lie beyond buffer 0's 392"},
      {"from the placeholder", [&](GltfFile& f) { ext(f, 0)["buffer"] = 1; },
       view0 + "buffer 1 is a placeholder without data"},
      {"uncompressed view on the placeholder",
       [&](GltfFile& f) { f.json["bufferViews"][0].erase("extensions"); },
       "bufferView 0: buffer 1 is a placeholder without data (EXT_meshopt_compression), and the "
       "view is not compressed"},
      {"over --max-triangles", [](GltfFile&) {}, "8 triangles exceed the limit of 7", 7},
  };
  const TestMesh mesh = gridMesh(2);
  for (const BadInput& c : cases) {
    SCOPED_TRACE(c.name);
    GltfFile f = meshoptMeshFile(mesh, false, false);
    c.change(f);
    const std::string path = writeFile("bad.glb", f);
    LoadOptions options;
    options.maxTriangles = c.maxTriangles;
    EXPECT_EQ(loadError(path, options), path + ": " + c.message);
  }
}

// Decoded bytes count against --max-file-bytes before they are allocated.
TEST(Compression, MeshoptDecodedBytesAreHeldToTheFileLimit) {
  const TestMesh mesh = gridMesh(40);
  const std::string path = writeFile("big.glb", meshoptMeshFile(mesh, false, false));
  LoadOptions options;
  options.maxFileBytes = fs::file_size(path) + 100;
  EXPECT_EQ(loadError(path, options),
            path +
                ": bufferView 1: EXT_meshopt_compression: the decoded views exceed the limit "
                "of " +
                std::to_string(options.maxFileBytes) + " bytes (--max-file-bytes)");
}

// Seeds for the loader's fuzzer (ci/sanitize.sh), self-contained GLBs reaching every decode
// path: written into $MANYLIGHT_FUZZ_SEEDS when it is set, else into the test folder; each
// must load.
TEST(Compression, FuzzSeedsLoad) {
  const char* env = std::getenv("MANYLIGHT_FUZZ_SEEDS");
  const fs::path dir = env ? fs::path(env) : testFolder();
  const TestMesh mesh = gridMesh(3);
  const std::pair<const char*, GltfFile> seeds[] = {
      {"draco-edgebreaker.glb", dracoMeshFile(mesh, true)},
      {"draco-sequential.glb", dracoMeshFile(mesh, false)},
      {"meshopt.glb", meshoptMeshFile(mesh, false, false)},
      {"meshopt-filters-indices.glb", meshoptMeshFile(mesh, true, true)},
  };
  for (const auto& [name, file] : seeds) {
    writeGltf((dir / name).string(), file);
    EXPECT_EQ(loadError((dir / name).string()), "") << name;
  }
}

}  // namespace
}  // namespace manylight::testing
