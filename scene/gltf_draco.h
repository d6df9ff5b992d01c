#pragma once
// KHR_draco_mesh_compression: a primitive's vertex data and indices decoded from its Draco
// bitstream (Draco bitstream 2.2, the version the extension is written against) with
// Debian's libdraco. Internal to scene/.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace manylight::gltf {

// Whether `primitive` carries KHR_draco_mesh_compression.
bool hasDraco(const tinygltf::Primitive& primitive);

class DracoPrimitive {
 public:
  // Decodes the primitive's Draco data. Before the decoder runs, the triangle and vertex
  // counts the bitstream's connectivity header declares are checked against the accessors'
  // counts (which the loader has held to --max-triangles), so a small bitstream cannot make
  // the decoder allocate for more; after it, the decoded mesh is checked against them again.
  // Throws SceneError("`where`: KHR_draco_mesh_compression: problem").
  DracoPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                 const std::string& where);
  ~DracoPrimitive();
  DracoPrimitive(const DracoPrimitive&) = delete;
  DracoPrimitive& operator=(const DracoPrimitive&) = delete;

  // Whether the extension maps glTF attribute `name` to a Draco attribute.
  bool has(const std::string& name) const;
  // Attribute `name` as floats, `components` per vertex (the accessor's type must have that
  // many, and so must the Draco attribute); integer data is normalised when the accessor
  // says so. Throws SceneError.
  std::vector<float> floats(const std::string& name, int components) const;
  // The decoded triangles' vertex indices, three per triangle.
  std::vector<std::uint32_t> indices() const;

 private:
  struct Decoded;
  std::unique_ptr<Decoded> d_;
};

}  // namespace manylight::gltf
