#pragma once
// Helpers shared by the tests, no GL: temporary folders, generated scenes, the corpus.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "generators/scene_builder.h"
#include "scene/gltf_loader.h"

namespace manylight::testing {

// A fresh folder under the system temp folder, unique to this test; removed at exit.
std::filesystem::path testFolder();

// Writes `text` to NAME in the test folder and returns its path.
std::string writeFile(const std::string& name, const std::string& text);

// The message loadGltf throws for `path` (SceneError), or "" when it loads.
std::string loadError(const std::string& path, const LoadOptions& options = {});

// Writes the room scene with `options` into the test folder and returns its path.
std::string roomScene(const RoomOptions& options, const std::string& name = "room.gltf");

// The room scene with one light and no textures, loaded once per process. (GL tests open
// their context first: its driver is loaded by dlopen, which waits on the image module's.)
const Scene& untexturedRoom();

// Writes, in the test folder, NAME.gltf and NAME.bin: a camera on node 1, child of node 0
// (translated by (1, 0, 0)); animation 0 moves node 1 from z = 5 to 10 to 15 at t = 0,
// `secondTime`, 2 (`interpolation`) and turns it 90° about +Y at the second key (STEP).
// Returns the .gltf's path.
std::string animatedScene(const std::string& name, const char* interpolation = "LINEAR",
                          float secondTime = 1.0f);

// Where failing render tests put their actual and diff images.
std::filesystem::path artefactFolder();

// The files the corpus tests walk, sorted: the project's own scenes/ always (so the walk is
// never empty), and every .gltf/.glb of ../shared/scenes when that folder exists (in CI).
std::vector<std::filesystem::path> corpusFiles();

// A corpus file's name in reports: relative to ../shared/scenes, or "scenes/NAME".
std::string corpusName(const std::filesystem::path& file);

}  // namespace manylight::testing
