#include "tests/test_support.h"

#include <algorithm>

#include <unistd.h>

#include <gtest/gtest.h>

namespace manylight::testing {

namespace fs = std::filesystem;

fs::path testFolder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
  static const fs::path root = fs::temp_directory_path() / ("manylight-test-" + std::to_string(::getpid()));
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

std::string roomScene(const RoomOptions& options, const std::string& name) {
  const std::string path = (testFolder() / name).string();
  writeRoomScene(path, options);
  return path;
}

gl::Context& context() {
  static std::unique_ptr<gl::Context> ctx = gl::createContext(gl::Backend::Auto);
  return *ctx;
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

}  // namespace manylight::testing
