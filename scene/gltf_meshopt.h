#pragma once
// EXT_meshopt_compression: buffer views whose data is stored compressed in another buffer,
// decoded at load time with Debian's libmeshoptimizer into a buffer of their own, which the
// views then point at, so that accessors read them as any other view. Internal to scene/.
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace manylight::gltf {

// Decodes every buffer view with EXT_meshopt_compression (modes ATTRIBUTES, TRIANGLES,
// INDICES; filters NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL) into one new buffer and points
// the views at it. The extension's fields are checked as its specification says, and the
// decoded bytes in all against `maxBytes` (--max-file-bytes), before anything is allocated.
// `placeholders`: the buffers scene/gltf_parse.h found without data; a view still on one
// afterwards has no data, and is an error. Throws
// SceneError("bufferView N: EXT_meshopt_compression: problem").
void decodeMeshoptViews(tinygltf::Model& model, const std::vector<int>& placeholders,
                        std::uintmax_t maxBytes);

}  // namespace manylight::gltf
