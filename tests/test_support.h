#pragma once
// Helpers shared by the tests: temporary folders, generated scenes, a GL context per process.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "gl/context.h"
#include "scene/scene_builder.h"

namespace manylight::testing {

// A fresh folder under the system temp folder, unique to this test; removed at exit.
std::filesystem::path testFolder();

// Writes the room scene with `options` into the test folder and returns its path.
std::string roomScene(const RoomOptions& options, const std::string& name = "room.gltf");

// The process's GL context (auto backend), created on first use.
gl::Context& context();

// Where failing render tests put their actual and diff images.
std::filesystem::path artefactFolder();

// The files the corpus tests walk, sorted: the project's own scenes/ always (so the walk is
// never empty), and every .gltf/.glb of ../shared/scenes when that folder exists (in CI).
std::vector<std::filesystem::path> corpusFiles();

// A corpus file's name in reports: relative to ../shared/scenes, or "scenes/NAME".
std::string corpusName(const std::filesystem::path& file);

}  // namespace manylight::testing
