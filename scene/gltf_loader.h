#pragma once
// Loads glTF 2.0 (.gltf with external, embedded or data-URI buffers, and .glb) into a Scene,
// using tinygltf for JSON, base64 and GLB parsing and OpenImageIO for texture images.
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace manylight {

struct LoadOptions {
  // Lights beyond this count make the load fail (the process's light budget).
  std::size_t lightBudget = 1u << 20;
  // Bytes the scene may read in all: the glTF/GLB file and its external buffers and images.
  std::uintmax_t maxFileBytes = std::uintmax_t(1) << 30;
};

// Throws SceneError ("FILE: problem") when the file cannot be read, is not valid glTF 2.0,
// requires an extension or version we do not support, or exceeds the light budget.
// Points and lines are skipped with a warning in Scene::warnings.
Scene loadGltf(const std::string& path, const LoadOptions& options = {});

}  // namespace manylight
