#include "bake/light_tree_pack.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/constants.hpp>

#include "bake/light_tree_layout.h"

namespace manylight {
namespace {

std::uint32_t bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

}  // namespace

PackedTrees packLightTrees(const std::vector<LightTree>& trees) {
  PackedTrees packed;
  std::size_t texels = 0;
  for (const LightTree& tree : trees) {
    const int stride = tree.type == LightType::Spot ? layout::kSpotNodeTexels : layout::kNodeTexels;
    texels += tree.nodes.size() * stride;
  }
  packed.texels.assign(texels * 4, 0u);
  std::size_t next = 0;
  for (const LightTree& tree : trees) {
    const int t = int(tree.type == LightType::Directional ? 0 : tree.type == LightType::Point ? 1 : 2);
    const int stride = t == 2 ? layout::kSpotNodeTexels : layout::kNodeTexels;
    packed.base[t] = int(next);
    packed.leaves[t] = tree.leafCount;
    for (const LightTreeNode& n : tree.nodes) {
      std::uint32_t* w = &packed.texels[next * 4];
      w[0] = bits(n.boxMin.x), w[1] = bits(n.boxMin.y), w[2] = bits(n.boxMin.z);
      w[3] = std::uint32_t(n.representative);
      w[4] = bits(n.boxMax.x), w[5] = bits(n.boxMax.y), w[6] = bits(n.boxMax.z);
      w[7] = bits(n.invRange2);
      w[8] = bits(n.intensity.r), w[9] = bits(n.intensity.g), w[10] = bits(n.intensity.b);
      if (t == 1) w[11] = bits(n.invRange2Max);
      if (t == 2) {
        // 1e-4 rad of margin covers the float rounding of the cone merges.
        const double theta = std::min(double(n.spread) + double(n.outerAngle) + 1e-4, glm::pi<double>());
        w[11] = bits(float(std::cos(theta)));
        w[12] = bits(n.axis.x), w[13] = bits(n.axis.y), w[14] = bits(n.axis.z);
        w[15] = bits(float(std::sin(theta)));
      }
      next += stride;
    }
  }
  return packed;
}

}  // namespace manylight
