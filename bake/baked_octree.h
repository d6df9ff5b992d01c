#pragma once
// The baked file's octree section (docs/baked-format.md): the linkless octree of the
// octree method, as bake/linkless_octree.h lays it out. Internal to bake/.
#include "bake/baked_sections.h"
#include "bake/linkless_octree.h"

namespace manylight::baked {

inline constexpr std::uint32_t kOctree = tag("OCTR");

void writeOctree(Writer& w, const LinklessOctree& o);

// Reads an octree for `lights` lights and checks what the shader relies on: levels within
// kMaxOctreeLevels, each level's table and offsets inside the arrays and of its dims, every
// leaf's list inside the index list, every index a light. Throws BakeError via `r`.
LinklessOctree readOctree(Reader& r, std::size_t lights);

}  // namespace manylight::baked
