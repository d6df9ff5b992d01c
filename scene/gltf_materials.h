#pragma once
// Converts glTF materials and their textures into scene/ types, each once, on first use:
// the core metallic-roughness material with all five textures, alpha modes, and the
// extensions that change a picture (KHR_texture_transform, KHR_materials_emissive_strength,
// KHR_materials_unlit, KHR_materials_pbrSpecularGlossiness). Internal to scene/.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace tinygltf {
class Model;
class Value;
struct TextureInfo;
}  // namespace tinygltf

namespace manylight::gltf {

class MaterialConverter {
 public:
  MaterialConverter(const tinygltf::Model& model, Scene& scene);

  // Index into Scene::materials of glTF material `index`. Throws SceneError.
  int material(int index);

 private:
  // A texture of the material, or none (with a warning) where its image cannot be used.
  TextureRef textureRef(int materialIndex, const char* what, const tinygltf::TextureInfo& info,
                        int index, int texCoord, bool srgb);
  int texture(int index, bool srgb);
  // KHR_materials_pbrSpecularGlossiness `ext` of material `index` into `m`.
  void specularGlossiness(int index, const tinygltf::Value& ext, Material& m);

  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<int> materials_;                    // glTF index → scene index, −1 if not yet
  std::map<std::pair<int, bool>, int> textures_;  // (glTF texture, sRGB) → scene index
};

}  // namespace manylight::gltf
