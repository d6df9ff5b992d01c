// libFuzzer target for the glTF loader (clang, -DMANYLIGHT_FUZZ=ON; run by ci/sanitize.sh).
// Each input is written to a file (.glb when it starts with the GLB magic, else .gltf) in a
// private folder and loaded under small limits, through the whole loader: simdjson over the
// nodes and lights (scene/gltf_bulk.cpp), tinygltf over the rest. A SceneError is the expected way
// to fail; anything else — another exception, a crash, a sanitizer report — is a bug, and the input
// that caused it belongs in tests/regressions/ with a test. ci/sanitize.sh seeds it with the
// corpus's small files and Draco and meshopt GLBs (tests/compression_test.cpp, FuzzSeedsLoad).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "base/error.h"
#include "scene/gltf_loader.h"

namespace {

const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    auto d =
        std::filesystem::temp_directory_path() / ("manylight-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const auto path = folder() / (binary ? "input.glb" : "input.gltf");
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  manylight::LoadOptions limits;
  limits.maxFileBytes = 8u << 20;
  limits.maxTextureDimension = 1024;
  limits.maxTexturePixels = 1 << 20;
  limits.maxTriangles = 1 << 20;
  limits.lightBudget = 1 << 16;
  try {
    manylight::loadGltf(path.string(), limits);
  } catch (const manylight::SceneError&) {
  }
  return 0;
}
