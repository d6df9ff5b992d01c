#pragma once
// Walks the node hierarchy of a glTF file's default scene (§3.5), placing meshes, lights and
// cameras in the Scene. Internal to scene/; scene/gltf_loader.cpp drives it after
// checkStructure has ruled out cycles and second parents.
#include <cstddef>
#include <exception>
#include <vector>

#include "scene/gltf_animation.h"
#include "scene/gltf_bulk.h"
#include "scene/gltf_convert.h"
#include "scene/gltf_loader.h"

namespace manylight::gltf {

class SceneWalker {
 public:
  SceneWalker(const tinygltf::Model& model, const BulkArrays& bulk, Scene& scene,
              Converter& convert, const LoadOptions& options)
      : model_(model), bulk_(bulk), scene_(scene), convert_(convert), options_(options) {}

  // Places every node under the default scene's roots (every node that is nobody's child
  // when there are no scenes), depth first, root by root. Many distinct roots that are
  // nobody's children (kParallelRoots or more: a scene listing each light as a root), with
  // no more lights than the budget, are walked in shares on several threads; the Scene, and
  // the error thrown for a faulty file, are those of one walk in order. Throws SceneError.
  void walk();

  // Where each of Scene::lights comes from, in order.
  const std::vector<LightSource>& lightSources() const { return lightSources_; }

  static constexpr std::size_t kParallelRoots = 65536;

 private:
  struct Item {
    int node;
    glm::mat4 parent;
  };
  // A node's mesh or camera, placed when the shares are merged: converting a mesh fills the
  // converter's cache, which one thread at a time may do.
  struct Use {
    bool camera;
    int node, index;
    glm::mat4 world;
  };
  // What the walk of some of the roots placed, in walk order, and the error that stopped it.
  struct Share {
    std::vector<Light> lights;  // at most the light budget
    std::vector<LightSource> sources;
    std::size_t lightsSeen = 0;
    std::vector<Use> uses;
    std::exception_ptr error;
  };

  std::vector<int> roots() const;
  int sharesFor(const std::vector<int>& roots) const;
  void walkShare(const int* first, const int* last, Share& out, std::vector<char>& visited) const;
  void place(int index, const NodeRecord& node, const glm::mat4& world, Share& out) const;
  void merge(Share& share);

  const tinygltf::Model& model_;
  const BulkArrays& bulk_;
  Scene& scene_;
  Converter& convert_;
  const LoadOptions& options_;
  std::vector<bool> cameraPlaced_;
  std::vector<int> parent_;
  std::size_t lightsSeen_ = 0;
  std::vector<LightSource> lightSources_;
};

}  // namespace manylight::gltf
