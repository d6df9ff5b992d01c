// libFuzzer target for light lists (clang, -DMANYLIGHT_FUZZ=ON; run by ci/sanitize.sh). The
// first byte picks the format (by the file extension the reader goes by), the rest is the
// file. A SceneError is the expected way to fail; anything else is a bug.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "base/error.h"
#include "scene/light_list.h"

namespace {

const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() /
             ("manylight-fuzz-lights-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* extensions[] = {".csv", ".json", ".txt"};
  const auto path = folder() / (std::string("lights") + extensions[data[0] % 3]);
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  }
  manylight::Scene scene;
  manylight::LoadOptions limits;
  limits.maxFileBytes = 1u << 20;
  limits.lightBudget = 1 << 12;
  try {
    manylight::appendLightList(path.string(), scene, limits);
  } catch (const manylight::SceneError&) {
  }
  return 0;
}
