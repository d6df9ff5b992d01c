// Every glTF file of ../shared/scenes (when present): loads and renders, or fails with a
// one-line message naming the file. Never crashes or hangs (ctest's timeout catches hangs).
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "render/render_job.h"
#include "scene/error.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

// Folders of deliberately broken or edge-case files: they may load or fail, but a failure
// must be a clean one-line message.
const std::set<std::string> kDefectFolders = {
    "glTF-Validator-tests", "assimp-glTF2-defects", "tinygltf-defects", "MagnumGltfImporterTests",
    "glTFast-test-models", "BlenderIO-edge-cases"};

// Well-formed assets that require an extension we do not implement: the glTF spec says a
// loader must refuse them, and we do, naming the extension.
const std::set<std::string> kNeedUnsupportedExtension = {
    "AnimateAllTheThings", "GlamVelvetSofa"};

// What must happen to a file: render, fail with a message containing `reason`, or either
// (defect folders).
struct Expectation {
  bool mayRender;
  bool mayFail;
  std::string reason;
};

std::string topFolder(const fs::path& file) {
  return fs::relative(file, MANYLIGHT_SHARED_SCENES).begin()->string();
}

Expectation expectationFor(const fs::path& file) {
  const std::string top = topFolder(file);
  const std::string name = file.filename().string();
  if (kDefectFolders.count(top)) return {true, true, ""};
  if (file.string().find("Draco") != std::string::npos || kNeedUnsupportedExtension.count(top)) {
    return {false, true, "required extension"};
  }
  // The glTF-Asset-Generator README: 00–03 must load, 04 (minVersion 2.1) and 05 (an
  // unknown required extension) must fail.
  if (name == "Compatibility_04.gltf") return {false, true, "asset.minVersion 2.1"};
  if (name == "Compatibility_05.gltf") return {false, true, "required extension"};
  return {true, false, ""};
}

std::vector<fs::path> corpusFiles() {
  std::vector<fs::path> files;
  const fs::path root = MANYLIGHT_SHARED_SCENES;
  if (!fs::exists(root)) return files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string ext = e.path().extension().string();
    if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(Corpus, EveryFileRendersOrFailsCleanly) {
  const std::vector<fs::path> files = corpusFiles();
  if (files.empty()) {
    // Not a skip: without the shared folder there is nothing to walk, and the project's own
    // tests cover the loader. Say so in the log.
    std::cout << "no shared scenes at " << MANYLIGHT_SHARED_SCENES << "\n";
    return;
  }
  context();
  int rendered = 0, failed = 0;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    const Expectation expect = expectationFor(file);
    try {
      const Scene scene = loadGltf(file.string());
      RenderRequest request;
      request.width = 48;
      request.height = 36;
      const RenderOutcome out = renderScene(scene, request);
      ++rendered;
      EXPECT_TRUE(expect.mayRender) << "loaded, but should have been refused";
      if (!expect.mayFail && !scene.instances.empty()) {
        float brightest = 0.0f;
        for (std::size_t i = 0; i < out.image.rgba.size(); i += 4) {
          brightest = std::max({brightest, out.image.rgba[i], out.image.rgba[i + 1], out.image.rgba[i + 2]});
        }
        EXPECT_GT(brightest, 0.0f) << "rendered black";
      }
    } catch (const Error& e) {
      ++failed;
      const std::string msg = e.what();
      EXPECT_TRUE(expect.mayFail) << "well-formed file failed: " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
      EXPECT_EQ(msg.rfind(file.string() + ": ", 0), 0u) << "message does not name the file: " << msg;
      if (!expect.reason.empty()) {
        EXPECT_NE(msg.find(expect.reason), std::string::npos) << msg;
      }
    }
  }
  std::cout << files.size() << " files: " << rendered << " rendered, " << failed << " refused\n";
}

}  // namespace
}  // namespace manylight::testing
