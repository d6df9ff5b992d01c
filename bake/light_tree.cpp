#include "bake/light_tree.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <glm/gtc/constants.hpp>
#include <limits>

namespace manylight {
namespace {

constexpr double kPi = glm::pi<double>();

// A light as the builder sees it: where it is (directional: its direction on the unit
// sphere), what it emits, and its texture slot.
struct Item {
  glm::vec3 point;
  glm::vec3 axis;  // spot: the way it shines
  glm::vec3 intensity;
  float invRange2;
  float outerAngle;
  int slot;
};

double scalar(glm::vec3 i) { return double(i.r) + double(i.g) + double(i.b); }

// The smallest cone holding cones a and b (Conty Estevez & Kulla 2018, Algorithm 1).
void mergeCones(glm::vec3& axis, float& spread, glm::vec3 axisB, float spreadB) {
  glm::dvec3 a(axis), b(axisB);
  double ta = spread, tb = spreadB;
  if (tb > ta) std::swap(a, b), std::swap(ta, tb);
  const double td = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  if (std::min(td + tb, kPi) <= ta) {
    axis = glm::vec3(a), spread = float(ta);
    return;
  }
  const double to = (ta + td + tb) / 2.0;
  if (to >= kPi) {
    axis = glm::vec3(a), spread = float(kPi);
    return;
  }
  // Rotate a towards b by to − ta.
  glm::dvec3 w = b - a * glm::dot(a, b);
  if (glm::dot(w, w) < 1e-24)
    w = std::abs(a.x) < 0.9 ? glm::cross(a, {1, 0, 0}) : glm::cross(a, {0, 1, 0});
  w = glm::normalize(w);
  const double r = to - ta;
  axis = glm::vec3(glm::normalize(a * std::cos(r) + w * std::sin(r)));
  spread = float(to);
}

Item itemOf(const Light& l, int slot) {
  Item it;
  it.point = l.type == LightType::Directional ? -l.direction : l.position;
  it.axis = l.direction;
  it.intensity = l.colour * l.intensity;
  it.invRange2 = l.range > 0.0f && std::isfinite(l.range) ? 1.0f / (l.range * l.range) : 0.0f;
  it.outerAngle = l.type == LightType::Spot ? l.outerConeAngle : 0.0f;
  it.slot = slot;
  return it;
}

LightTreeNode leafNode(const Item& it) {
  LightTreeNode n;
  n.boxMin = n.boxMax = it.point;
  n.intensity = it.intensity;
  n.representative = it.slot;
  n.invRange2 = n.invRange2Max = it.invRange2;
  n.axis = it.axis;
  n.spread = 0.0f;
  n.outerAngle = it.outerAngle;
  return n;
}

// Deterministic uniform number in [0, 1) for node `index` (splitmix64).
double uniform(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed + (index + 1) * 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-53;
}

// `cones`: the spot lights' tree, whose nodes bound their lights' directions; the other
// trees' nodes keep the left child's axis and no spread, which nothing reads.
LightTreeNode mergeNodes(const LightTreeNode& l, const LightTreeNode& r, double u, bool cones) {
  if (l.empty()) return r;
  if (r.empty()) return l;
  LightTreeNode n;
  n.boxMin = glm::min(l.boxMin, r.boxMin);
  n.boxMax = glm::max(l.boxMax, r.boxMax);
  n.intensity = l.intensity + r.intensity;
  const double il = scalar(l.intensity), ir = scalar(r.intensity);
  // Representative: the left child's with probability I_left / (I_left + I_right).
  n.representative =
      (il + ir > 0.0 ? u * (il + ir) < il : u < 0.5) ? l.representative : r.representative;
  n.invRange2 =
      (l.invRange2 == 0.0f || r.invRange2 == 0.0f) ? 0.0f : std::min(l.invRange2, r.invRange2);
  n.invRange2Max = std::max(l.invRange2Max, r.invRange2Max);
  n.axis = l.axis;
  n.spread = l.spread;
  n.outerAngle = std::max(l.outerAngle, r.outerAngle);
  if (!cones) return n;
  mergeCones(n.axis, n.spread, r.axis, r.spread);
  // The axis is stored in float: widen the spread until it holds both children's cones as
  // stored, measured in double (plus a float step), so the bound stays conservative.
  for (const LightTreeNode* c : {&l, &r}) {
    const double angle = std::acos(std::clamp(
        glm::dot(glm::normalize(glm::dvec3(n.axis)), glm::normalize(glm::dvec3(c->axis))), -1.0,
        1.0));
    n.spread =
        std::max(n.spread, std::nextafter(float(std::min(angle + double(c->spread), kPi)), 4.0f));
  }
  return n;
}

// A range of items [first, last) of a builder, split at `mid` by the median along an axis:
// 0–2 position, 3–5 the spot axis scaled by the scene diagonal.
struct Splitter {
  bool oriented;  // spot lights: directions count in the metric
  double c;       // scene diagonal

  // The selection with the axis fixed at compile time: no branch on it per comparison (the
  // builder's most frequent operation).
  template <int Axis>
  void partitionAlong(Item* first, Item* mid, Item* last) const {
    const float scale = float(c);
    std::nth_element(first, mid, last, [scale](const Item& a, const Item& b) {
      if constexpr (Axis < 3) {
        return a.point[Axis] < b.point[Axis];
      } else {
        return scale * a.axis[Axis - 3] < scale * b.axis[Axis - 3];
      }
    });
  }

  void partition(Item* first, Item* mid, Item* last, int axis) const {
    switch (axis) {
      case 0:
        return partitionAlong<0>(first, mid, last);
      case 1:
        return partitionAlong<1>(first, mid, last);
      case 2:
        return partitionAlong<2>(first, mid, last);
      case 3:
        return partitionAlong<3>(first, mid, last);
      case 4:
        return partitionAlong<4>(first, mid, last);
      default:
        return partitionAlong<5>(first, mid, last);
    }
  }

  // Metric of the items as one cluster. The cone is the one around the mean direction (not
  // the smallest, which would need trigonometry per light): good enough to rank splits.
  double metricOf(const Item* first, const Item* last) const {
    glm::vec3 mn = first->point, mx = mn, sum(0.0f), axisSum(0.0f);
    for (const Item* it = first; it != last; ++it) {
      mn = glm::min(mn, it->point);
      mx = glm::max(mx, it->point);
      sum += it->intensity;
      axisSum += it->axis;
    }
    double cone = 0.0;
    if (oriented && glm::dot(axisSum, axisSum) > 0.0f) {
      const glm::vec3 mean = glm::normalize(axisSum);
      float cosSpread = 1.0f;
      for (const Item* it = first; it != last; ++it)
        cosSpread = std::min(cosSpread, glm::dot(mean, it->axis));
      cone = c * (1.0 - double(cosSpread));
    } else if (oriented) {
      cone = 2.0 * c;
    }
    const glm::dvec3 d = glm::dvec3(mx) - glm::dvec3(mn);
    return scalar(sum) * (glm::dot(d, d) + cone * cone);
  }

  // The axis whose median split has the smallest summed metric; leaves the range split
  // along it.
  int bestAxis(Item* first, Item* mid, Item* last) const {
    int best = 0;
    double bestCost = std::numeric_limits<double>::infinity();
    const int axes = oriented ? 6 : 3;
    for (int axis = 0; axis < axes; ++axis) {
      partition(first, mid, last, axis);
      const double cost = metricOf(first, mid) + metricOf(mid, last);
      if (cost < bestCost) bestCost = cost, best = axis;
    }
    if (best != axes - 1) partition(first, mid, last, best);
    return best;
  }
};

// Ranges of more items than this choose their split axis on an evenly strided sample of
// kSplitSample of them, then split once along it: each axis tried over a range that large
// costs a selection and two metric passes over memory that no cache holds (at 2^20 mixed
// lights, the top three levels of each tree: a sixth of the build). Below it every split
// is exact: sampled splits from 4,096 lights up measured a 99th-percentile error a tenth
// higher at 65,536 mixed lights, where at 2^20 lights the sampled top levels change neither
// errors nor cut sizes (docs/performance.md).
constexpr int kSampledSplitAbove = 65536;
constexpr int kSplitSample = 1024;

struct Builder {
  std::vector<Item> items;
  std::vector<LightTreeNode>* nodes;
  Split split;
  Splitter axes;
  bool cones;  // spot lights: nodes bound their directions
  std::uint64_t seed;

  void chooseAndPartition(int lo, int mid, int hi) {
    Item* const first = items.data() + lo;
    if (split == Split::LongestAxis) {
      glm::vec3 mn = items[lo].point, mx = mn;
      for (int i = lo + 1; i < hi; ++i)
        mn = glm::min(mn, items[i].point), mx = glm::max(mx, items[i].point);
      const glm::vec3 e = mx - mn;
      axes.partition(first, first + (mid - lo), first + (hi - lo),
                     e.x >= e.y && e.x >= e.z ? 0
                     : e.y >= e.z             ? 1
                                              : 2);
      return;
    }
    const int n = hi - lo;
    if (n <= kSampledSplitAbove) {
      axes.bestAxis(first, first + (mid - lo), first + (hi - lo));
      return;
    }
    std::vector<Item> sample(kSplitSample);
    for (int k = 0; k < kSplitSample; ++k)
      sample[std::size_t(k)] = first[std::int64_t(k) * n / kSplitSample];
    const int best = axes.bestAxis(sample.data(), sample.data() + kSplitSample / 2,
                                   sample.data() + kSplitSample);
    axes.partition(first, first + (mid - lo), first + (hi - lo), best);
  }

  // Fills node `index` (with `capacity` leaves below it) from items [lo, hi).
  void build(int index, int capacity, int lo, int hi, int depth) {
    LightTreeNode& node = (*nodes)[index];
    if (capacity == 1) {
      node = hi > lo ? leafNode(items[lo]) : LightTreeNode{};
      return;
    }
    const int left = 2 * index + 1, right = 2 * index + 2;
    if (hi == lo) {
      // An empty subtree: nodes are already value-initialised as empty.
      return;
    }
    const int mid = lo + (hi - lo + 1) / 2;
    if (hi - lo > 1) chooseAndPartition(lo, mid, hi);
    // The top levels build their halves on two threads (the halves touch disjoint items and
    // nodes); below, one thread each.
    if (depth < 2 && hi - lo > 4096) {
      auto half =
          std::async(std::launch::async, [&] { build(left, capacity / 2, lo, mid, depth + 1); });
      build(right, capacity / 2, mid, hi, depth + 1);
      half.get();
    } else {
      build(left, capacity / 2, lo, mid, depth + 1);
      build(right, capacity / 2, mid, hi, depth + 1);
    }
    node = mergeNodes((*nodes)[left], (*nodes)[right], uniform(seed, std::uint64_t(index)), cones);
  }
};

}  // namespace

double clusterMetric(const LightTreeNode& node, double c) {
  if (node.empty()) return 0.0;
  const glm::dvec3 d = glm::dvec3(node.boxMax) - glm::dvec3(node.boxMin);
  const double alpha2 = glm::dot(d, d);
  const double cone = c > 0.0 ? c * (1.0 - std::cos(double(node.spread))) : 0.0;
  return scalar(node.intensity) * (alpha2 + cone * cone);
}

std::vector<LightTree> buildLightTrees(const std::vector<Light>& lights,
                                       const TreeOptions& options) {
  const LightOrder order = lightOrder(lights);
  // The scene diagonal c of the metric: over the positions of point and spot lights.
  glm::dvec3 mn(std::numeric_limits<double>::max()), mx(-std::numeric_limits<double>::max());
  for (const Light& l : lights) {
    if (l.type != LightType::Directional)
      mn = glm::min(mn, glm::dvec3(l.position)), mx = glm::max(mx, glm::dvec3(l.position));
  }
  const double c = mx.x >= mn.x ? glm::length(mx - mn) : 0.0;

  std::vector<LightTree> trees;
  const int starts[4] = {0, order.pointStart, order.spotStart, int(order.scene.size())};
  const LightType types[3] = {LightType::Directional, LightType::Point, LightType::Spot};
  for (int t = 0; t < 3; ++t) {
    const int count = starts[t + 1] - starts[t];
    if (count == 0) continue;
    Builder b;
    b.items.reserve(count);
    for (int slot = starts[t]; slot < starts[t + 1]; ++slot)
      b.items.push_back(itemOf(lights[order.scene[slot]], slot));
    LightTree tree;
    tree.type = types[t];
    tree.leafCount = 1;
    while (tree.leafCount < count) tree.leafCount *= 2;
    tree.nodes.assign(std::size_t(2) * tree.leafCount - 1, LightTreeNode{});
    b.nodes = &tree.nodes;
    b.split = options.split;
    b.axes.oriented = tree.type == LightType::Spot && options.coneWeight > 0.0;
    b.cones = tree.type == LightType::Spot;
    b.axes.c = c * options.coneWeight;
    b.seed = options.seed ^ std::uint64_t(t);
    b.build(0, tree.leafCount, 0, count, 0);
    trees.push_back(std::move(tree));
  }
  return trees;
}

bool refitLightTrees(std::vector<LightTree>& trees, const std::vector<Light>& lights,
                     const std::vector<int>& changed, const TreeOptions& options) {
  const LightOrder order = lightOrder(lights);
  std::vector<int> slotOf(lights.size(), -1);
  for (std::size_t slot = 0; slot < order.scene.size(); ++slot)
    slotOf[order.scene[slot]] = int(slot);
  // The tree and leaf of each light texture slot, from the leaves' representatives.
  std::vector<std::pair<int, int>> leafOf(lights.size(), {-1, -1});
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const LightTree& tree = trees[t];
    for (int i = tree.firstLeaf(); i < int(tree.nodes.size()); ++i) {
      const int slot = tree.nodes[std::size_t(i)].representative;
      if (slot < 0) continue;
      if (std::size_t(slot) >= leafOf.size()) return false;
      leafOf[std::size_t(slot)] = {int(t), i};
    }
  }
  std::vector<std::vector<char>> dirty(trees.size());
  for (std::size_t t = 0; t < trees.size(); ++t) dirty[t].assign(trees[t].nodes.size(), 0);
  for (int index : changed) {
    const int slot = slotOf[std::size_t(index)];
    const auto [t, leaf] = leafOf[std::size_t(slot)];
    if (t < 0 || trees[std::size_t(t)].type != lights[std::size_t(index)].type) return false;
    trees[std::size_t(t)].nodes[std::size_t(leaf)] =
        leafNode(itemOf(lights[std::size_t(index)], slot));
    dirty[std::size_t(t)][std::size_t(leaf)] = 1;
  }
  for (std::size_t t = 0; t < trees.size(); ++t) {
    LightTree& tree = trees[t];
    // The seed buildLightTrees gave this type's tree, so a node keeps its draw.
    const int typeIndex = tree.type == LightType::Directional ? 0
                          : tree.type == LightType::Point     ? 1
                                                              : 2;
    const std::uint64_t seed = options.seed ^ std::uint64_t(typeIndex);
    for (int i = tree.firstLeaf() - 1; i >= 0; --i) {
      const std::size_t l = std::size_t(2 * i + 1), r = l + 1;
      if (!dirty[t][l] && !dirty[t][r]) continue;
      tree.nodes[std::size_t(i)] =
          mergeNodes(tree.nodes[l], tree.nodes[r], uniform(seed, std::uint64_t(i)),
                     tree.type == LightType::Spot);
      dirty[t][std::size_t(i)] = 1;
    }
  }
  return true;
}

}  // namespace manylight
