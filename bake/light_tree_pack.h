#pragma once
// Packs light trees into the node texture (see bake/light_tree_layout.h).
#include <cstdint>
#include <vector>

#include "bake/light_tree.h"

namespace manylight {

struct PackedTrees {
  std::vector<std::uint32_t> texels;  // 4 words per texel
  // Per light type (0 directional, 1 point, 2 spot): first texel and leaf count (0: no tree).
  int base[3] = {0, 0, 0};
  int leaves[3] = {0, 0, 0};
};

PackedTrees packLightTrees(const std::vector<LightTree>& trees);

}  // namespace manylight
