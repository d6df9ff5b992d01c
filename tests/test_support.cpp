#include "tests/test_support.h"

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

}  // namespace manylight::testing
