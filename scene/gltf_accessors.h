#pragma once
// Bounds-checked reading of glTF accessors (strided, normalised, sparse) into flat arrays.
// Internal to scene/.
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace manylight::gltf {

// Reads accessor `index` as floats, `components` per element (1..4; a type with that many
// components is required). Normalised integer types are converted as the glTF spec says.
// Throws SceneError naming `what` and the accessor when it does not fit its buffer.
std::vector<float> readFloats(const tinygltf::Model& model, int index, int components,
                              const std::string& what);

// Reads an index accessor (unsigned byte, short or int scalars).
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index);

// One component of glTF type `componentType` at `p` as a float, normalised integers converted
// as the glTF spec says (as readFloats does).
float componentAsFloat(const unsigned char* p, int componentType, bool normalized);

// The bytes of bufferView `index`. Throws SceneError naming `what` when the view does not
// exist or does not lie within its buffer.
struct ViewBytes {
  const unsigned char* data;
  std::size_t size;
};
ViewBytes bufferViewBytes(const tinygltf::Model& model, int index, const std::string& what);

}  // namespace manylight::gltf
