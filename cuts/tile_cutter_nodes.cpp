// TileCutter's nodes (cuts/tile_cuts.h): the packed trees decoded once, each node with
// its representative's light beside it.
#include <algorithm>
#include <cstddef>
#include <type_traits>

#include "bake/light_pack.h"
#include "bake/light_tree_layout.h"
#include "bake/parallel.h"
#include "cuts/node_lanes.h"
#include "cuts/tile_cuts.h"

namespace manylight {

using layout::floatOf;

namespace {
// Fewer nodes than this a thread are decoded on one.
constexpr std::size_t kNodesPerThread = 65536;
}  // namespace

TileCutter::TileCutter(const PackedTrees& packed, const std::vector<Light>& lights)
    : colour_(packed.colour) {
  const LightOrder order = lightOrder(lights);  // the light texture's slots
  std::vector<SpotConeTerms> cones;             // per spot slot, from order.spotStart
  for (std::size_t slot = std::size_t(order.spotStart); slot < lights.size(); ++slot)
    cones.push_back(spotConeTerms(lights[std::size_t(order.scene[slot])]));
  int slots = 0;
  for (int t = 0; t < 3; ++t) {
    leaves_[t] = packed.leaves[t];
    const std::size_t count = leaves_[t] > 0 ? std::size_t(2 * leaves_[t] - 1) : 0;
    static_assert(std::is_trivially_default_constructible_v<Node>);
    nodes_[t].reset(new Node[count]);
    runOnShares(sharesOf(count, kNodesPerThread), count,
                [&](int, std::size_t from, std::size_t to) {
                  for (std::size_t i = from; i < to; ++i) nodes_[t][i] = decode(packed, t, int(i));
                });
    for (int i = leaves_[t] - 1; i < 2 * leaves_[t] - 1; ++i) {
      slots = std::max(slots, node(t, i).representative + 1);
    }
  }
  // Each node carries its representative's light, so that an estimate reads no second node.
  std::vector<int> leafOfSlot(std::size_t(slots), -1);
  for (int t = 0; t < 3; ++t) {
    for (int i = leaves_[t] - 1; i < 2 * leaves_[t] - 1; ++i) {
      const int slot = node(t, i).representative;
      if (slot >= 0) leafOfSlot[std::size_t(slot)] = i;
    }
    const auto carry = [&](Node& n) {
      if (n.representative < 0) return;
      const Node& l = node(t, leafOfSlot[std::size_t(n.representative)]);
      n.repPoint = l.boxMin;
      n.repInvRange2 = l.invRange2;
      n.repAxis = l.axis;
      n.repCos = l.w2;
      if (t == 2) {
        const SpotConeTerms& cone = cones[std::size_t(n.representative - order.spotStart)];
        n.repConeScale = cone.scale;
        n.repConeOffset = cone.offset;
      }
    };
    const std::size_t count = leaves_[t] > 0 ? std::size_t(2 * leaves_[t] - 1) : 0;
    runOnShares(sharesOf(count, kNodesPerThread), count,
                [&](int, std::size_t from, std::size_t to) {
                  for (std::size_t i = from; i < to; ++i) carry(nodes_[t][i]);
                });
  }
}

TileCutter::Node TileCutter::decode(const PackedTrees& packed, int tree, int i) {
  // gatherNodes reads a node's first kNodeRows floats as NodeLanes' rows.
  static_assert(offsetof(Node, leafRow) == (kNodeRows - 1) * sizeof(float) &&
                offsetof(Node, repPoint) == offsetof(NodeLanes, repPoint) / kLanes &&
                offsetof(Node, leafRow) == offsetof(NodeLanes, leaf) / kLanes);
  const std::uint32_t* w = packed.words.data() + packed.base[tree] +
                           std::size_t(tree == 2 ? layout::kSpotNodeWords : layout::kNodeWords) * i;
  Node n;
  n.boxMin = {floatOf(w[0]), floatOf(w[1]), floatOf(w[2])};
  n.representative = int(w[3]);
  n.invRange2 = floatOf(w[7]);
  const bool leaf = i >= packed.leaves[tree] - 1;
  n.leafRow = leaf ? 1.0f : 0.0f;
  const glm::vec3 words46{floatOf(w[4]), floatOf(w[5]), floatOf(w[6])};
  n.boxMax = leaf ? n.boxMin : words46;
  n.intensity = leaf ? words46 : packed.colour.decode(w[8]);
  n.w2 = floatOf(w[9]);
  n.axis = tree == 2 ? glm::vec3(floatOf(w[10]), floatOf(w[11]), floatOf(w[12])) : glm::vec3(0.0f);
  n.sinTheta = tree == 2 ? floatOf(w[13]) : 0.0f;
  // The constructor carries the representative's light in.
  n.repPoint = n.repAxis = glm::vec3(0.0f);
  n.repInvRange2 = n.repCos = n.repConeScale = n.repConeOffset = 0.0f;
  return n;
}

}  // namespace manylight
