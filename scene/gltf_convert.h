#pragma once
// Converts glTF objects (meshes, materials, textures, lights, cameras) into scene/ types,
// each glTF object once, on first use. Internal to scene/.
#include <string>
#include <vector>

#include "scene/gltf_materials.h"
#include "scene/scene.h"

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace manylight::gltf {

struct BulkArrays;

// A primitive's mode, TRIANGLES when absent.
int primitiveMode(const tinygltf::Primitive& p);

// How many triangles a primitive of `mode` with `count` vertices (or indices) makes; 0 for
// points and lines.
long long triangleCount(int mode, long long count);

// The rotation and translation of `world`, scale removed (cameras).
glm::mat4 withoutScale(const glm::mat4& world);

// Places `light` by a node's world transform: position its origin, direction its −Z
// normalised (node scale changes neither range nor cone). False, and `light` unchanged, when
// the transform collapses the direction.
bool placeLight(Light& light, const glm::mat4& world);

class Converter {
 public:
  // `creaseRadians`: for normals built where a primitive has none (scene/half_edge.h).
  // Nodes and lights come from `bulk` (scene/gltf_bulk.h), the rest from `model`.
  Converter(const tinygltf::Model& model, const BulkArrays& bulk, Scene& scene,
            float creaseRadians);

  // Index into Scene::meshes of glTF mesh `index`. Throws SceneError.
  int mesh(int index);
  // glTF camera `index` with an identity placement.
  Camera camera(int index) const;
  // glTF light `index` placed by a node's world transform. Throws SceneError.
  Light light(int index, const glm::mat4& world) const;

 private:
  Primitive primitive(int meshIndex, int primIndex);

  const tinygltf::Model& model_;
  const BulkArrays& bulk_;
  Scene& scene_;
  std::vector<int> meshes_;  // glTF index → scene index, −1 if not yet
  MaterialConverter materials_;
  float creaseRadians_;
};

}  // namespace manylight::gltf
