#pragma once
// Baked scenes (`manylight bake`): everything a render needs, precomputed, in one versioned
// binary file that kiosk playback and thumbnail services load without rebuilding anything:
// meshes with index buffers and normals, materials, decoded textures, lights (a light list
// already added), cameras, the packed light trees with their node colour coding, and the
// light octree. The
// format is documented in docs/baked-format.md; this file and that document change
// together. No GL.
#include <cstdint>
#include <string>
#include <string_view>

#include "bake/light_octree.h"
#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "bake/linkless_octree.h"
#include "scene/scene.h"

namespace manylight {

inline constexpr char kBakedMagic[8] = {'M', 'L', 'B', 'A', 'K', 'E', '\r', '\n'};
inline constexpr std::uint32_t kBakedFormatVersion = 3;
inline constexpr std::size_t kBakedHeaderBytes = 32;  // magic, version, flags, file size, checksum

struct BakedScene {
  Scene scene;
  TreeOptions trees;      // how the trees were built and packed
  bool hasTrees = false;  // false when the scene has no lights (the default rig is lit at render)
  PackedTrees packed;
  // The octree method's octree, baked when some light has a range (without one the method
  // is the reference loop and needs nothing baked).
  bool hasOctree = false;
  LinklessOctree octree;
};

// Builds and packs the light trees of `scene` with `trees`, and its octree with `octree`.
BakedScene bakeScene(Scene scene, const TreeOptions& trees, const OctreeOptions& octree = {});

// Writes `baked` to `path` through a temporary file. Throws Error.
void writeBakedScene(const std::string& path, const BakedScene& baked);

// The header's checksum of the bytes after the header (docs/baked-format.md).
std::uint64_t bakedChecksum(std::string_view bytes);

// Whether `path` starts with the baked file magic.
bool isBakedFile(const std::string& path);

// Reads a baked file of at most maxBytes. Throws BakeError "PATH: problem" for a file that
// is not one (magic), another format version, a truncated or altered file (sizes, checksum),
// or contents that break the format's invariants (indices out of range, counts that do not
// add up).
BakedScene readBakedScene(const std::string& path, std::uint64_t maxBytes = std::uint64_t(4) << 30);

}  // namespace manylight
