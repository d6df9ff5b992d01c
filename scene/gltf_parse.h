#pragma once
// Runs tinygltf on a scene file. Debian's tinygltf is built without Draco, and refuses two
// things the compression extensions allow, so the JSON is amended first (only in files that
// use those extensions) and the model restored after:
// - KHR_draco_mesh_compression: a primitive's indices accessor without a bufferView (its data
//   is in the Draco bitstream): tinygltf requires one. The primitive's `indices` is held back
//   from tinygltf and put back into the model.
// - EXT_meshopt_compression: a placeholder buffer, with no uri and no data, only the
//   byteLength of the views decoded into it: tinygltf requires a uri in a .gltf and takes a
//   GLB's from the binary chunk. It is given a one-byte data: URI instead, emptied after.
// - KHR_animation_pointer: a channel target without a node: tinygltf drops the channel. It
//   is given node −1, what tinygltf sets for a target without one.
// Internal to scene/.
#include <cstdint>
#include <string>

namespace tinygltf {
class Model;
class TinyGLTF;
}  // namespace tinygltf

namespace manylight {
class AssetFiles;
}

namespace manylight::gltf {
struct BulkArrays;

// Parses the glTF (or, with `binary`, GLB) file at `path`: its nodes and lights into *bulk
// (scene/gltf_bulk.h), the rest with tinygltf into *model, read through `files` so that it
// counts against the byte limit, as TinyGLTF::LoadASCIIFromFile / LoadBinaryFromFile would;
// `base` is the folder its URIs are relative to. Returns tinygltf's result, its messages in
// *err and *warn. When it succeeds, decodes the EXT_meshopt_compression views
// (scene/gltf_meshopt.h, at most `maxDecodedBytes`), which throws SceneError.
bool parseGltfFile(tinygltf::TinyGLTF& parser, tinygltf::Model* model, BulkArrays* bulk,
                   std::string* err, std::string* warn, const std::string& path,
                   const std::string& base, bool binary, AssetFiles& files,
                   std::uintmax_t maxDecodedBytes);

}  // namespace manylight::gltf
