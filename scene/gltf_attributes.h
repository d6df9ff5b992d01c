#pragma once
// Where a primitive's vertex data and indices come from: its accessors, or, for attributes its
// KHR_draco_mesh_compression extension maps, the mesh the Draco bitstream decodes to. The
// converter reads every attribute through this, so the two sources differ in one place.
// Internal to scene/.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace manylight::gltf {

class DracoPrimitive;

class AttributeSource {
 public:
  // Decodes the primitive's Draco data, if it has any. `where` ("mesh M primitive P")
  // prefixes Draco's errors. Throws SceneError.
  AttributeSource(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                  const std::string& where);
  ~AttributeSource();
  AttributeSource(const AttributeSource&) = delete;
  AttributeSource& operator=(const AttributeSource&) = delete;

  // The accessor of attribute `name` (it gives count and type whatever the source); −1 when
  // the primitive has no such attribute.
  int accessor(const std::string& name) const;
  // Attribute `name` as floats, `components` per vertex (readFloats' rules). Throws SceneError.
  std::vector<float> floats(const std::string& name, int components) const;
  // Whether the primitive has indices, and they (unchecked against the vertex count).
  bool hasIndices() const;
  std::vector<std::uint32_t> indices() const;

 private:
  const tinygltf::Model& model_;
  const tinygltf::Primitive& primitive_;
  std::unique_ptr<DracoPrimitive> draco_;  // null without KHR_draco_mesh_compression
};

}  // namespace manylight::gltf
