#include "bake/light_tree.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <future>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <utility>

#include "base/parallel.h"

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

// Fewer lights or nodes than this a thread are sorted or filled on one.
constexpr std::size_t kPerThread = 16384;

// A light as the builder orders it: where it is (directional: its direction on the unit
// sphere), what it emits, and its index among its tree's lights.
struct Key {
  glm::vec3 point;
  glm::vec3 intensity;
  int index;
};

// Builds one tree from its lights kept in order along each split axis (0–2 position, 3–5
// the spot direction): a node's lights are one range [lo, hi) of every order, so the median
// split along an axis is that axis's order cut at its middle, and a split keeps the other
// orders by one stable partition each. Nothing is selected or sorted again below the root:
// each level costs a metric pass and a partition per axis over memory read in sequence.
struct Builder {
  const std::vector<Light>* lights;
  const std::vector<int>* scene;  // lightOrder's texture slot → scene index
  int firstSlot;                  // the slot of the tree's light 0
  std::vector<LightTreeNode>* nodes;
  Split split;
  bool oriented;  // spot lights: directions count in the metric
  double c;       // scene diagonal, times the cone weight
  bool cones;     // spot lights: nodes bound their directions
  std::uint64_t seed;
  int axisCount = 3;
  std::vector<glm::vec3> direction;  // per index, when oriented
  std::vector<Key> order[6];
  std::vector<Key> scratch;
  std::vector<std::uint8_t> inRight;  // per index: in the right half of the split being made
  std::vector<int> leafKey;           // per leaf: the index of its light; −1: none

  void sortOrders(int count) {
    axisCount = oriented ? 6 : 3;
    std::vector<Key> keys(static_cast<std::size_t>(count));
    if (oriented) direction.resize(std::size_t(count));
    for (int i = 0; i < count; ++i) {
      const Item it = itemOf((*lights)[std::size_t((*scene)[std::size_t(firstSlot + i)])], 0);
      keys[std::size_t(i)] = {it.point, it.intensity, i};
      if (oriented) direction[std::size_t(i)] = it.axis;
    }
    const int shares =
        std::min(axisCount, sharesOf(keys.size() * std::size_t(axisCount), kPerThread));
    runOnShares(shares, std::size_t(axisCount), [&](int, std::size_t from, std::size_t to) {
      for (std::size_t axis = from; axis < to; ++axis) sortAlong(int(axis), keys);
    });
    scratch.resize(std::size_t(count));
    inRight.resize(std::size_t(count));
  }

  float coordinate(const Key& k, int axis) const {
    return axis < 3 ? k.point[axis] : direction[std::size_t(k.index)][axis - 3];
  }

  // order[axis]: the keys by their coordinate along it, ties by index (so builds repeat):
  // a stable radix sort, in three passes of 11 bits, of the coordinates' bits turned into
  // unsigned integers of the same order (−0 taken as +0, as a comparison would).
  void sortAlong(int axis, const std::vector<Key>& keys) {
    const std::size_t count = keys.size();
    std::vector<std::uint64_t> ranked(count), spare(count);
    for (std::size_t i = 0; i < count; ++i) {
      const float x = coordinate(keys[i], axis);
      std::uint32_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      if (x == 0.0f) bits = 0;
      bits = bits >> 31 ? ~bits : bits | 0x80000000u;
      ranked[i] = std::uint64_t(bits) << 32 | i;
    }
    for (int shift = 32; shift < 64; shift += 11) {
      std::vector<std::size_t> start(2049, 0);
      for (const std::uint64_t r : ranked) ++start[((r >> shift) & 2047) + 1];
      for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
      for (const std::uint64_t r : ranked) spare[start[(r >> shift) & 2047]++] = r;
      ranked.swap(spare);
    }
    std::vector<Key>& out = order[axis];
    out.resize(count);
    for (std::size_t i = 0; i < count; ++i) out[i] = keys[ranked[i] & 0xffffffffu];
  }

  // Metric of the keys as one cluster. The cone is the one around the mean direction (not
  // the smallest, which would need trigonometry per light): good enough to rank splits.
  double metricOf(const Key* first, const Key* last) const {
    glm::vec3 mn = first->point, mx = mn, sum(0.0f), axisSum(0.0f);
    for (const Key* it = first; it != last; ++it) {
      mn = glm::min(mn, it->point);
      mx = glm::max(mx, it->point);
      sum += it->intensity;
    }
    double cone = 0.0;
    if (oriented) {
      for (const Key* it = first; it != last; ++it) axisSum += direction[std::size_t(it->index)];
      if (glm::dot(axisSum, axisSum) > 0.0f) {
        const glm::vec3 mean = glm::normalize(axisSum);
        float cosSpread = 1.0f;
        for (const Key* it = first; it != last; ++it)
          cosSpread = std::min(cosSpread, glm::dot(mean, direction[std::size_t(it->index)]));
        cone = c * (1.0 - double(cosSpread));
      } else {
        cone = 2.0 * c;
      }
    }
    const glm::dvec3 d = glm::dvec3(mx) - glm::dvec3(mn);
    return scalar(sum) * (glm::dot(d, d) + cone * cone);
  }

  // The axis to split [lo, hi) along at mid: the one whose median split has the smallest
  // summed metric (Split::Metric), or the longest of the lights' box.
  int chooseAxis(int lo, int mid, int hi) const {
    if (split == Split::LongestAxis) {
      const Key* first = order[0].data();
      glm::vec3 mn = first[lo].point, mx = mn;
      for (int i = lo + 1; i < hi; ++i)
        mn = glm::min(mn, first[i].point), mx = glm::max(mx, first[i].point);
      const glm::vec3 e = mx - mn;
      return e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
    }
    int best = 0;
    double bestCost = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < axisCount; ++axis) {
      const Key* first = order[axis].data();
      const double cost = metricOf(first + lo, first + mid) + metricOf(first + mid, first + hi);
      if (cost < bestCost) bestCost = cost, best = axis;
    }
    return best;
  }

  // Splits [lo, hi) at mid along `axis`: every other order keeps its halves' keys in order.
  void splitAt(int lo, int mid, int hi, int axis) {
    // Local pointers: stores through the byte array could otherwise alias the vectors'.
    std::uint8_t* const side = inRight.data();
    Key* const out = scratch.data();
    const Key* const cut = order[axis].data();
    for (int i = lo; i < mid; ++i) side[cut[i].index] = 0;
    for (int i = mid; i < hi; ++i) side[cut[i].index] = 1;
    for (int other = 0; other < axisCount; ++other) {
      if (other == axis) continue;
      Key* const keys = order[other].data();
      int l = lo, r = mid;
      for (int i = lo; i < hi; ++i) {
        // Without a branch: which half a light goes to is as good as random.
        const int toRight = side[keys[i].index];
        out[toRight ? r : l] = keys[i];
        r += toRight;
        l += 1 - toRight;
      }
      std::copy(out + lo, out + hi, keys + lo);
    }
  }

  // Splits node `index`'s lights [lo, hi) down to its leaves (`capacity` of them below it),
  // each taking its light's index in leafKey.
  void splitDown(int index, int capacity, int lo, int hi, int depth) {
    if (hi == lo) return;  // an empty subtree: its nodes stay empty
    if (capacity == 1) {
      leafKey[std::size_t(index + 1) - leafKey.size()] = order[0][std::size_t(lo)].index;
      return;
    }
    const int left = 2 * index + 1, right = 2 * index + 2;
    const int mid = lo + (hi - lo + 1) / 2;
    if (hi - lo > 1) splitAt(lo, mid, hi, chooseAxis(lo, mid, hi));
    // The top levels split their halves on two threads (the halves touch disjoint ranges of
    // every array and disjoint leaves); below, one thread each.
    if (depth < 2 && hi - lo > 4096) {
      auto half =
          std::async(kThreadOrDeferred, [&] { splitDown(left, capacity / 2, lo, mid, depth + 1); });
      splitDown(right, capacity / 2, mid, hi, depth + 1);
      half.get();
    } else {
      splitDown(left, capacity / 2, lo, mid, depth + 1);
      splitDown(right, capacity / 2, mid, hi, depth + 1);
    }
  }

  // Fills the leaves from their lights, then each level of internal nodes from the one
  // below, in shares (a leaf reads its light from anywhere in memory: many reads in flight).
  void fillNodes() {
    const std::size_t leafCount = leafKey.size();
    std::vector<LightTreeNode>& n = *nodes;
    runOnShares(sharesOf(leafCount, kPerThread), leafCount,
                [&](int, std::size_t from, std::size_t to) {
                  for (std::size_t i = from; i < to; ++i) {
                    if (leafKey[i] < 0) continue;
                    const int slot = firstSlot + leafKey[i];
                    n[leafCount - 1 + i] =
                        leafNode(itemOf((*lights)[std::size_t((*scene)[std::size_t(slot)])], slot));
                  }
                });
    for (std::size_t width = leafCount / 2; width >= 1; width /= 2) {
      runOnShares(sharesOf(width, kPerThread), width, [&](int, std::size_t from, std::size_t to) {
        for (std::size_t i = width - 1 + from; i < width - 1 + to; ++i)
          n[i] = mergeNodes(n[2 * i + 1], n[2 * i + 2], uniform(seed, i), cones);
      });
    }
  }

  void build(int count, int leafCount) {
    sortOrders(count);
    leafKey.assign(std::size_t(leafCount), -1);
    splitDown(0, leafCount, 0, count, 0);
    fillNodes();
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

  const int starts[4] = {0, order.pointStart, order.spotStart, int(order.scene.size())};
  const LightType types[3] = {LightType::Directional, LightType::Point, LightType::Spot};
  // The types' trees are built at once: each one's top levels and sorts leave cores idle.
  LightTree built[3];
  runOnThreads(3, [&](int t) {
    const int count = starts[t + 1] - starts[t];
    if (count == 0) return;
    LightTree& tree = built[t];
    tree.type = types[t];
    tree.leafCount = 1;
    while (tree.leafCount < count) tree.leafCount *= 2;
    tree.nodes.assign(std::size_t(2) * tree.leafCount - 1, LightTreeNode{});
    Builder b;
    b.lights = &lights;
    b.scene = &order.scene;
    b.firstSlot = starts[t];
    b.nodes = &tree.nodes;
    b.split = options.split;
    b.oriented =
        tree.type == LightType::Spot && options.coneWeight > 0.0 && options.split == Split::Metric;
    b.cones = tree.type == LightType::Spot;
    b.c = c * options.coneWeight;
    b.seed = options.seed ^ std::uint64_t(t);
    b.build(count, tree.leafCount);
  });
  std::vector<LightTree> trees;
  for (LightTree& tree : built) {
    if (tree.leafCount > 0) trees.push_back(std::move(tree));
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
