#include "bake/light_tree_pack.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <utility>

#include "bake/light_tree_layout.h"
#include "base/parallel.h"

namespace manylight {
namespace {

using layout::wordOf;

int typeIndex(LightType type) {
  return type == LightType::Directional ? 0 : type == LightType::Point ? 1 : 2;
}

// The intensities the shader decodes: internal, non-empty nodes (leaves are exact).
std::vector<glm::vec3> decodedIntensities(const std::vector<LightTree>& trees) {
  std::vector<glm::vec3> colours;
  for (const LightTree& tree : trees) {
    for (int i = 0; i < tree.firstLeaf(); ++i) {
      if (!tree.nodes[i].empty()) colours.push_back(tree.nodes[i].intensity);
    }
  }
  return colours;
}

// Fewer nodes than this a thread are packed on one.
constexpr std::size_t kNodesPerThread = 65536;

// Node i of `tree` (type index t) into its words at `w`.
void packNode(const LightTree& tree, int i, int t, const NodeColourCoder& colour,
              std::uint32_t* w) {
  const LightTreeNode& n = tree.nodes[std::size_t(i)];
  w[0] = wordOf(n.boxMin.x), w[1] = wordOf(n.boxMin.y), w[2] = wordOf(n.boxMin.z);
  w[3] = std::uint32_t(n.representative);
  if (i < tree.firstLeaf()) {
    w[4] = wordOf(n.boxMax.x), w[5] = wordOf(n.boxMax.y), w[6] = wordOf(n.boxMax.z);
    w[layout::kColourWord] = colour.encode(n.intensity);
  } else {  // a leaf's box is its light's position: the words hold its exact intensity
    w[4] = wordOf(n.intensity.r), w[5] = wordOf(n.intensity.g), w[6] = wordOf(n.intensity.b);
  }
  w[7] = wordOf(n.invRange2);
  if (t == 1) w[9] = wordOf(n.invRange2Max);
  if (t == 2) {
    // 1e-4 rad of margin covers the float rounding of the cone merges.
    const double theta =
        std::min(double(n.spread) + double(n.outerAngle) + 1e-4, glm::pi<double>());
    w[9] = wordOf(float(std::cos(theta)));
    w[10] = wordOf(n.axis.x), w[11] = wordOf(n.axis.y), w[12] = wordOf(n.axis.z);
    w[13] = wordOf(float(std::sin(theta)));
  }
}

}  // namespace

PackedTrees packLightTrees(const std::vector<LightTree>& trees, NodeColourCoding coding) {
  const std::vector<glm::vec3> colours = decodedIntensities(trees);
  PackedTrees packed{
      {}, {0, 0, 0}, {0, 0, 0}, NodeColourCoder(coding, colours, NodeColourCoder::Unmeasured{})};
  std::size_t words = 0;
  for (const LightTree& tree : trees) {
    words += tree.nodes.size() *
             (tree.type == LightType::Spot ? layout::kSpotNodeWords : layout::kNodeWords);
  }
  words = (words + 3) / 4 * 4;
  if (words > std::size_t(1) << 31)
    throw BakeError("the light trees need " + std::to_string(words) + " words, more than 2^31");
  packed.words.assign(words, 0u);
  std::size_t next = 0;
  for (const LightTree& tree : trees) {
    const int t = typeIndex(tree.type);
    packed.base[t] = int(next);
    packed.leaves[t] = tree.leafCount;
    const std::size_t stride = t == 2 ? layout::kSpotNodeWords : layout::kNodeWords;
    std::uint32_t* const out = &packed.words[next];
    // Nodes write disjoint words: shares of them are packed on threads at once. Internal
    // nodes (which encode a colour) and leaves are shared apart, so that each thread gets
    // as many of the costly ones.
    const std::size_t firstLeaf = std::size_t(tree.firstLeaf());
    const std::pair<std::size_t, std::size_t> ranges[2] = {{0, firstLeaf},
                                                           {firstLeaf, tree.nodes.size()}};
    for (const auto& range : ranges) {
      const std::size_t begin = range.first, count = range.second - range.first;
      runOnShares(sharesOf(count, kNodesPerThread), count,
                  [&](int, std::size_t from, std::size_t to) {
                    for (std::size_t i = begin + from; i < begin + to; ++i)
                      packNode(tree, int(i), t, packed.colour, out + stride * i);
                  });
    }
    next += stride * tree.nodes.size();
  }
  // The coder measured on the words just packed, in decodedIntensities' order.
  std::vector<std::uint32_t> colourWords;
  colourWords.reserve(colours.size());
  for (const LightTree& tree : trees) {
    const int t = typeIndex(tree.type);
    const std::size_t stride = t == 2 ? layout::kSpotNodeWords : layout::kNodeWords;
    for (int i = 0; i < tree.firstLeaf(); ++i) {
      if (!tree.nodes[std::size_t(i)].empty())
        colourWords.push_back(packed.words[std::size_t(packed.base[t]) + stride * std::size_t(i) +
                                           layout::kColourWord]);
    }
  }
  packed.colour.measure(colours, colourWords);
  return packed;
}

PackedTrees bakeLightTrees(const std::vector<Light>& lights, const TreeOptions& options) {
  return packLightTrees(buildLightTrees(lights, options), options.nodeColour);
}

}  // namespace manylight
