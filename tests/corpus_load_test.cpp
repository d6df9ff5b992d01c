// Every file of corpusFiles() (the project's scenes, and ../shared/scenes when present)
// through the loader alone, no GL: it
// loads, or fails with a one-line SceneError naming the file. This is the walk the
// sanitizer build runs (ci/sanitize.sh); corpus_gltest.cpp renders the same files.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "base/error.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

TEST(CorpusLoad, EveryFileLoadsOrFailsCleanly) {
  int tried = 0, loaded = 0, rejected = 0;
  for (const fs::path& file : corpusFiles()) {
    const std::string path = file.string();
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
  std::cout << "corpus: " << tried << " files, " << loaded << " loaded, " << rejected
            << " rejected\n";
  EXPECT_GT(loaded, 0);  // at least the project's own sample scene
}

}  // namespace
}  // namespace manylight::testing
