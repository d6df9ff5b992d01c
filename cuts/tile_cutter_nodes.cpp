// TileCutter's nodes (cuts/tile_cuts.h): the packed trees decoded block by block as cuts
// reach them, each node with its representative's light beside it.
#include <algorithm>
#include <cstddef>
#include <thread>
#include <type_traits>

#include "bake/light_tree_layout.h"
#include "cuts/node_lanes.h"
#include "cuts/tile_cuts.h"

namespace manylight {

using layout::floatOf;

namespace {

// The words of node i of tree t.
const std::uint32_t* wordsOf(const PackedTrees& packed, int t, int i) {
  return packed.words.data() + packed.base[t] +
         std::size_t(t == 2 ? layout::kSpotNodeWords : layout::kNodeWords) * std::size_t(i);
}

}  // namespace

TileCutter::TileCutter(PackedTrees packed, const std::vector<Light>& lights)
    : packed_(std::move(packed)), colour_(packed_.colour) {
  const LightOrder order = lightOrder(lights);  // the light texture's slots
  spotStart_ = order.spotStart;
  cones_.reserve(lights.size() - std::size_t(order.spotStart));
  for (std::size_t slot = std::size_t(order.spotStart); slot < lights.size(); ++slot)
    cones_.push_back(spotConeTerms(lights[std::size_t(order.scene[slot])]));
  // A node carries its representative's light, so that an estimate reads no second node:
  // the leaf of each slot, from the leaves' words.
  leafOfSlot_.assign(lights.size(), -1);
  for (int t = 0; t < 3; ++t) {
    leaves_[t] = packed_.leaves[t];
    const std::size_t count = leaves_[t] > 0 ? std::size_t(2 * leaves_[t] - 1) : 0;
    static_assert(std::is_trivially_default_constructible_v<Node>);
    nodes_[t].reset(new Node[count]);  // untouched until decoded
    const std::size_t blocks = (count >> kBlockShift) + 1;
    state_[t].reset(new std::atomic<std::uint8_t>[blocks]);
    for (std::size_t b = 0; b < blocks; ++b) state_[t][b].store(kRaw, std::memory_order_relaxed);
    for (int i = leaves_[t] - 1; i < 2 * leaves_[t] - 1; ++i) {
      const int slot = int(wordsOf(packed_, t, i)[3]);
      if (slot >= 0 && std::size_t(slot) < leafOfSlot_.size()) leafOfSlot_[std::size_t(slot)] = i;
    }
  }
}

void TileCutter::decodeBlock(int tree, std::size_t block) const {
  std::atomic<std::uint8_t>& state = state_[tree][block];
  std::uint8_t raw = kRaw;
  if (!state.compare_exchange_strong(raw, kDecoding, std::memory_order_acquire)) {
    while (state.load(std::memory_order_acquire) != kDecoded) std::this_thread::yield();
    return;
  }
  const int count = 2 * leaves_[tree] - 1;
  const int first = int(block << kBlockShift);
  const int last = std::min(count, first + (1 << kBlockShift));
  for (int i = first; i < last; ++i) nodes_[tree][std::size_t(i)] = decode(tree, i);
  state.store(kDecoded, std::memory_order_release);
}

TileCutter::Node TileCutter::decode(int tree, int i) const {
  // gatherNodes reads a node's first kNodeRows floats as NodeLanes' rows.
  static_assert(offsetof(Node, leafRow) == (kNodeRows - 1) * sizeof(float) &&
                offsetof(Node, repPoint) == offsetof(NodeLanes, repPoint) / kLanes &&
                offsetof(Node, leafRow) == offsetof(NodeLanes, leaf) / kLanes);
  const std::uint32_t* w = wordsOf(packed_, tree, i);
  Node n;
  n.boxMin = {floatOf(w[0]), floatOf(w[1]), floatOf(w[2])};
  n.representative = int(w[3]);
  n.invRange2 = floatOf(w[7]);
  const bool leaf = i >= leaves_[tree] - 1;
  n.leafRow = leaf ? 1.0f : 0.0f;
  const glm::vec3 words46{floatOf(w[4]), floatOf(w[5]), floatOf(w[6])};
  n.boxMax = leaf ? n.boxMin : words46;
  n.intensity = leaf ? words46 : colour_.decode(w[layout::kColourWord]);
  n.w2 = floatOf(w[9]);
  n.axis = tree == 2 ? glm::vec3(floatOf(w[10]), floatOf(w[11]), floatOf(w[12])) : glm::vec3(0.0f);
  n.sinTheta = tree == 2 ? floatOf(w[13]) : 0.0f;
  n.repPoint = n.repAxis = glm::vec3(0.0f);
  n.repInvRange2 = n.repCos = n.repConeScale = n.repConeOffset = 0.0f;
  if (n.representative < 0 || std::size_t(n.representative) >= leafOfSlot_.size() ||
      leafOfSlot_[std::size_t(n.representative)] < 0)
    return n;
  // The representative's light, as its leaf's words hold it.
  const std::uint32_t* l = wordsOf(packed_, tree, leafOfSlot_[std::size_t(n.representative)]);
  n.repPoint = {floatOf(l[0]), floatOf(l[1]), floatOf(l[2])};
  n.repInvRange2 = floatOf(l[7]);
  n.repCos = floatOf(l[9]);
  if (tree == 2) {
    n.repAxis = {floatOf(l[10]), floatOf(l[11]), floatOf(l[12])};
    const SpotConeTerms& cone = cones_[std::size_t(n.representative - spotStart_)];
    n.repConeScale = cone.scale;
    n.repConeOffset = cone.offset;
  }
  return n;
}

}  // namespace manylight
