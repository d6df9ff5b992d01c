#pragma once
// Loads glTF 2.0 (.gltf with external, embedded or data-URI buffers, and .glb) into a Scene,
// reading nodes and KHR_lights_punctual lights with simdjson (scene/gltf_bulk.h), the rest of
// the document with tinygltf (JSON, base64 and GLB parsing), and texture images with
// OpenImageIO.
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace manylight {

struct LoadOptions {
  // Lights beyond this count make the load fail (the process's light budget).
  std::size_t lightBudget = 1u << 20;
  // Bytes the scene may read in all: the glTF/GLB file and its external buffers and images.
  std::uintmax_t maxFileBytes = std::uintmax_t(1) << 30;
  // Textures: largest width or height, and most pixels (checked before decoding).
  std::int64_t maxTextureDimension = 16384;
  std::int64_t maxTexturePixels = std::int64_t(1) << 26;
  // Triangles over all meshes (checked before any vertex is read).
  std::int64_t maxTriangles = std::int64_t(1) << 26;
  // Normals built where a primitive has none are smooth across edges whose dihedral angle
  // is below this, split across sharper ones.
  float creaseAngleDegrees = 60.0f;
};

// Throws SceneError ("FILE: problem") when the file cannot be read, is not valid glTF 2.0,
// requires an extension or version we do not support, or exceeds a limit of `options`.
// Points and lines are skipped with a warning in Scene::warnings.
Scene loadGltf(const std::string& path, const LoadOptions& options = {});

}  // namespace manylight
