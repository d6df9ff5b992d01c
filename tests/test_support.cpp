#include "tests/test_support.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>

#include "base/error.h"
#include "scene/gltf_loader.h"

namespace manylight::testing {

namespace fs = std::filesystem;

fs::path testFolder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name =
      info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
  static const fs::path root =
      fs::temp_directory_path() / ("manylight-test-" + std::to_string(::getpid()));
  static const struct Cleanup {
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(root, ec);
    }
  } cleanup;
  const fs::path dir = root / name;
  fs::create_directories(dir);
  return dir;
}

std::string loadError(const std::string& path, const LoadOptions& options) {
  try {
    loadGltf(path, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = (testFolder() / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string roomScene(const RoomOptions& options, const std::string& name) {
  const std::string path = (testFolder() / name).string();
  writeRoomScene(path, options);
  return path;
}

const Scene& untexturedRoom() {
  static const Scene scene = [] {
    RoomOptions o;
    o.lightCount = 1;
    o.textured = false;
    return loadGltf(roomScene(o, "untextured-room.gltf"));
  }();
  return scene;
}

fs::path artefactFolder() {
  const fs::path dir = fs::current_path() / "test-artefacts";
  fs::create_directories(dir);
  return dir;
}

namespace {

bool isGltf(const std::filesystem::directory_entry& e) {
  const std::string ext = e.path().extension().string();
  return e.is_regular_file() && (ext == ".gltf" || ext == ".glb");
}

}  // namespace

std::vector<std::filesystem::path> corpusFiles() {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(MANYLIGHT_PROJECT_SCENES)) {
    if (isGltf(e)) files.push_back(e.path());
  }
  if (fs::exists(MANYLIGHT_SHARED_SCENES)) {
    for (const auto& e : fs::recursive_directory_iterator(MANYLIGHT_SHARED_SCENES)) {
      if (isGltf(e)) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string corpusName(const std::filesystem::path& file) {
  const std::filesystem::path shared = MANYLIGHT_SHARED_SCENES;
  const std::filesystem::path relative = file.lexically_relative(shared);
  if (!relative.empty() && *relative.begin() != "..") return relative.string();
  return "scenes/" + file.filename().string();
}

// A camera on node 1, child of node 0 (translated by (1, 0, 0)); animation 0 moves node 1
// from z = 5 to 10 to 15 at t = 0, 1, 2 (LINEAR), and turns it 90° about +Y at t = 1 (STEP).
std::string animatedScene(const std::string& name, const char* interpolation, float secondTime) {
  const float data[] = {
      0.0f, secondTime,  2.0f,                                                  // times
      0,    0,           5,    0,          0, 10,          0, 0,           15,  // translations
      0,    0,           0,    1,          0, 0.70710678f, 0, 0.70710678f,  // rotations at t = 0, 1
      0,    0.70710678f, 0,    0.70710678f};                                // and 2
  const std::string bin = (testFolder() / (name + ".bin")).string();
  std::ofstream(bin, std::ios::binary).write(reinterpret_cast<const char*>(data), sizeof data);
  const std::string gltf = R"({
    "asset": {"version": "2.0"},
    "buffers": [{"uri": ")" +
                           name + R"(.bin", "byteLength": )" + std::to_string(sizeof data) + R"(}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12},
                    {"buffer": 0, "byteOffset": 12, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 48}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "nodes": [{"translation": [1, 0, 0], "children": [1]}, {"camera": 0}],
    "scenes": [{"nodes": [0]}],
    "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}},
                                 {"sampler": 1, "target": {"node": 1, "path": "rotation"}}],
                    "samplers": [{"input": 0, "output": 1, "interpolation": ")" +
                           interpolation + R"("},
                                 {"input": 0, "output": 2, "interpolation": "STEP"}]}]
  })";
  const std::string path = (testFolder() / (name + ".gltf")).string();
  std::ofstream(path) << gltf;
  return path;
}

}  // namespace manylight::testing
