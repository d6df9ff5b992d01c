// Every glTF file of ../shared/scenes (when present) through the loader alone, no GL: it
// loads, or fails with a one-line SceneError naming the file. This is the walk the
// sanitizer build runs (ci/sanitize.sh); corpus_gltest.cpp renders the same files.
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>

#include "scene/error.h"
#include "scene/gltf_loader.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

TEST(CorpusLoad, EveryFileLoadsOrFailsCleanly) {
  const fs::path root = MANYLIGHT_SHARED_SCENES;
  if (!fs::exists(root)) GTEST_SKIP() << root << " is absent (it is present in CI)";
  int tried = 0, loaded = 0, rejected = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (!entry.is_regular_file() || (ext != ".gltf" && ext != ".glb")) continue;
    const std::string path = entry.path().string();
    ++tried;
    try {
      loadGltf(path);
      ++loaded;
    } catch (const SceneError& e) {
      ++rejected;
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  std::cout << "corpus: " << tried << " files, " << loaded << " loaded, " << rejected << " rejected\n";
  EXPECT_GT(tried, 0);
}

}  // namespace
}  // namespace manylight::testing
