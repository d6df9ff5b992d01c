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

// Fewer nodes than this a thread are packed on one.
constexpr std::size_t kNodesPerThread = 65536;

// Node i of `tree` (type index t) into its `stride` words at `w`.
void packNode(const LightTree& tree, int i, int t, const NodeColourCoder& colour, std::uint32_t* w,
              std::size_t stride) {
  const LightTreeNode& n = tree.nodes[std::size_t(i)];
  std::fill(w, w + stride, 0u);
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
  // The intensities the shader decodes, of every internal node of every tree in turn (leaves
  // are exact). An empty node's is black, which the coder neither fits nor measures.
  std::size_t internal = 0, used = 0;
  std::vector<std::size_t> firstColour;
  for (const LightTree& tree : trees) {
    firstColour.push_back(internal);
    internal += std::size_t(tree.firstLeaf());
    used += tree.nodes.size() *
            (tree.type == LightType::Spot ? layout::kSpotNodeWords : layout::kNodeWords);
  }
  const std::size_t words = (used + 3) / 4 * 4;
  if (words > std::size_t(1) << 31)
    throw BakeError("the light trees need " + std::to_string(words) + " words, more than 2^31");
  std::vector<glm::vec3> colours(internal);
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const std::vector<LightTreeNode>& nodes = trees[t].nodes;
    glm::vec3* const out = colours.data() + firstColour[t];
    const std::size_t count = std::size_t(trees[t].firstLeaf());
    runOnShares(sharesOf(count, kNodesPerThread), count,
                [&](int, std::size_t from, std::size_t to) {
                  for (std::size_t i = from; i < to; ++i) out[i] = nodes[i].intensity;
                });
  }
  PackedTrees packed{
      {}, {0, 0, 0}, {0, 0, 0}, NodeColourCoder(coding, colours, NodeColourCoder::Unmeasured{})};
  packed.words.resize(words);  // each node writes all its words; the padding is zeroed here
  std::fill(packed.words.begin() + std::ptrdiff_t(used), packed.words.end(), 0u);
  std::vector<std::uint32_t> colourWords(internal);  // in the colours' order
  std::size_t next = 0;
  for (std::size_t k = 0; k < trees.size(); ++k) {
    const LightTree& tree = trees[k];
    const int t = typeIndex(tree.type);
    packed.base[t] = int(next);
    packed.leaves[t] = tree.leafCount;
    const std::size_t stride = t == 2 ? layout::kSpotNodeWords : layout::kNodeWords;
    std::uint32_t* const out = &packed.words[next];
    std::uint32_t* const colourOut = colourWords.data() + firstColour[k];
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
                    for (std::size_t i = begin + from; i < begin + to; ++i) {
                      std::uint32_t* const w = out + stride * i;
                      packNode(tree, int(i), t, packed.colour, w, stride);
                      if (i < firstLeaf) colourOut[i] = w[layout::kColourWord];
                    }
                  });
    }
    next += stride * tree.nodes.size();
  }
  packed.colour.measure(colours, colourWords);
  return packed;
}

PackedTrees bakeLightTrees(const std::vector<Light>& lights, const TreeOptions& options) {
  return packLightTrees(buildLightTrees(lights, options), options.nodeColour);
}

}  // namespace manylight
