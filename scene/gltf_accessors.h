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

}  // namespace manylight::gltf
