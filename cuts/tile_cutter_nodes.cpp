// TileCutter's nodes (cuts/tile_cuts.h): the packed trees decoded block by block as cuts
// reach them, each node with its representative's light beside it.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <type_traits>
#include <vector>

#include "bake/light_tree_layout.h"
#include "cuts/node_lanes.h"
#include "cuts/threads.h"
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
  findSpotCones();
}

namespace {

// A spot node's lights, as findSpotCones gathers them bottom-up: the spread of their axes
// about the node's axis (an upper bound: a child's spread plus the angle between the axes;
// −1: no light) and the extreme cosines of their outer and inner angles, as the light
// texture's smoothstep terms give them, and their largest 1/range².
struct SpotLights {
  float spread = -1.0f;
  float outerLow = 1.0f, innerLow = 1.0f, outerHigh = -1.0f, innerHigh = -1.0f;
  float invRange2 = 0.0f;
};

// The node's axis from its words, unit length; none (zero) where the words hold none.
glm::dvec3 axisOf(const std::uint32_t* w) {
  const glm::dvec3 axis(floatOf(w[10]), floatOf(w[11]), floatOf(w[12]));
  return glm::length(axis) > 0.0 ? glm::normalize(axis) : glm::dvec3(0.0);
}

// x rounded to a float up (towards > 0) or down.
float roundedAway(double x, float towards) {
  const float f = float(x);
  const float limit = towards > 0.0f ? HUGE_VALF : -HUGE_VALF;
  return (towards > 0.0f ? double(f) < x : double(f) > x) ? std::nextafter(f, limit) : f;
}

}  // namespace

void TileCutter::findSpotCones() {
  const int leaves = leaves_[2];
  const int count = leaves > 0 ? 2 * leaves - 1 : 0;
  spotCones_.assign(std::size_t(count), SpotCone{});
  std::vector<SpotLights> lights(static_cast<std::size_t>(count));
  constexpr double kPi = 3.14159265358979323846;
  // The cones' terms, each widened (upper) or narrowed (lower) by 1e-6 in the cosine for
  // the float arithmetic of the shader's smoothstep (and of the cosines' floats here); the
  // spread's cosine rounded down, so that a spread below float's resolution near 1 still
  // counts (cos σ < 1, sin σ > 0).
  constexpr double kMargin = 1e-6;
  const auto node = [&](int i) {
    const std::uint32_t* w = wordsOf(packed_, 2, i);
    SpotLights& n = lights[std::size_t(i)];
    if (i >= leaves - 1) {
      const int slot = int(w[3]);
      if (slot < spotStart_ || std::size_t(slot - spotStart_) >= cones_.size()) return;
      const SpotConeTerms& cone = cones_[std::size_t(slot - spotStart_)];
      const double outer = -double(cone.offset) / double(cone.scale);
      const double inner = outer + 1.0 / double(cone.scale);
      n = {0.0f, float(outer), float(inner), float(outer), float(inner), floatOf(w[7])};
    } else {
      const glm::dvec3 axis = axisOf(w);
      for (const int k : {2 * i + 1, 2 * i + 2}) {
        const SpotLights& child = lights[std::size_t(k)];
        if (child.spread < 0.0f) continue;
        // The bake stores no zero axis for a node with lights; were one there: π.
        const glm::dvec3 childAxis = axisOf(wordsOf(packed_, 2, k));
        const double cosine = std::clamp(glm::dot(axis, childAxis), -1.0, 1.0);
        const double angle = axis == glm::dvec3(0.0) || childAxis == glm::dvec3(0.0)
                                 ? kPi
                                 : std::acos(cosine) + double(child.spread);
        n.spread = std::max(n.spread, roundedAway(std::min(angle, kPi), 1.0f));
        n.outerLow = std::min(n.outerLow, child.outerLow);
        n.innerLow = std::min(n.innerLow, child.innerLow);
        n.outerHigh = std::max(n.outerHigh, child.outerHigh);
        n.innerHigh = std::max(n.innerHigh, child.innerHigh);
        n.invRange2 = std::max(n.invRange2, child.invRange2);
      }
      if (n.spread < 0.0f) return;
    }
    SpotCone& c = spotCones_[std::size_t(i)];
    c.spreadCos = roundedAway(std::cos(std::min(double(n.spread) + kMargin, kPi)), -1.0f);
    const double upScale = 1.0 / (double(n.innerLow) - double(n.outerLow));
    c.upScale = float(upScale);
    c.upOffset = float(-(double(n.outerLow) - kMargin) * upScale);
    const double lowScale = 1.0 / (double(n.innerHigh) - double(n.outerHigh));
    c.lowScale = float(lowScale);
    c.lowOffset = float(-(double(n.outerHigh) + kMargin) * lowScale);
    c.lowInvRange2 = n.invRange2;
  };
  // Level by level from the leaves (the tree is complete): a level's nodes at once, on the
  // machine's threads where it is wide (at a million spots, 0.9 s on one thread).
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  for (int first = leaves - 1, width = leaves; width > 0; width /= 2, first = (first - 1) / 2) {
    const int parts = width >= 16384 ? threads : 1;
    onThreads(parts, [&](int part) {
      const int from = first + int(std::int64_t(width) * part / parts);
      const int to = first + int(std::int64_t(width) * (part + 1) / parts);
      for (int i = from; i < to; ++i) node(i);
    });
  }
}

std::vector<float> TileCutter::spotConeTexels() const {
  // Internal nodes only: they come first in the implicit layout, and a walk bounds no leaf.
  const std::size_t internal = leaves_[2] > 0 ? std::size_t(leaves_[2]) - 1 : 0;
  std::vector<float> texels;
  texels.reserve(8 * internal);
  for (std::size_t i = 0; i < internal; ++i) {
    const SpotCone& c = spotCones_[i];
    for (const float v :
         {c.spreadCos, c.upScale, c.upOffset, c.lowScale, c.lowOffset, c.lowInvRange2, 0.0f, 0.0f})
      texels.push_back(v);
  }
  return texels;
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
  static_assert(offsetof(Node, repConeOffset) == (kNodeRows - 1) * sizeof(float) &&
                offsetof(Node, repPoint) == offsetof(NodeLanes, repPoint) / kLanes &&
                offsetof(Node, leafRow) == offsetof(NodeLanes, leaf) / kLanes &&
                offsetof(Node, spreadCos) == offsetof(NodeLanes, spreadCos) / kLanes &&
                offsetof(Node, repConeOffset) == offsetof(NodeLanes, repConeOffset) / kLanes);
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
  const SpotCone cone = tree == 2 ? spotCones_[std::size_t(i)] : SpotCone{};
  n.spreadCos = cone.spreadCos;
  n.upScale = cone.upScale, n.upOffset = cone.upOffset;
  n.lowScale = cone.lowScale, n.lowOffset = cone.lowOffset;
  n.lowInvRange2 = cone.lowInvRange2;
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
