#pragma once
// Light trees for lightcuts (Walter et al. 2005): one complete binary tree per light type
// (directional, point, spot), in implicit layout — node i has children 2i+1 and 2i+2, the
// leaves are the last leafCount nodes — for any light count: missing leaves are empty
// (zero intensity), never a broken layout. No GL here; bake/light_tree_pack.h turns a
// forest into the node texture.
//
// Pairing: top-down, balanced. A node holding n lights gives ⌈n/2⌉ to its left child and
// ⌊n/2⌋ to its right (so every subtree's leaves still fit a power of two), split at the
// median of one axis. Split::Metric tries every axis (x, y, z; for spot lights, when
// TreeOptions::coneWeight > 0, also the three components of their directions) and
// keeps the one whose two halves have the smallest sum of the paper's cluster metric
// I_C·(α_C² + c²(1 − cos β_C)²); Split::LongestAxis takes the longest axis of the position
// box, the classic k-d split, kept as the baseline the metric split is measured against.
// Directional lights are points on the unit sphere (their direction towards the light), as
// in the paper.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "bake/light_pack.h"
#include "bake/node_colour.h"
#include "scene/scene.h"

namespace manylight {

struct LightTreeNode {
  glm::vec3 boxMin{0.0f}, boxMax{0.0f};  // positions (directional: directions) of its lights
  glm::vec3 intensity{0.0f};             // Σ colour · intensity, linear RGB
  int representative = -1;    // light texture slot (lightOrder) of the representative; −1: empty
  float invRange2 = 0.0f;     // 1/(largest range)²; 0 when any light has no range
  float invRange2Max = 0.0f;  // 1/(smallest range)²; 0 when no light has a range
  // Spot lights: a cone around `axis` holding every light's direction (half-angle `spread`),
  // and the widest outer cone angle of the lights.
  glm::vec3 axis{0.0f, 0.0f, -1.0f};
  float spread = 0.0f, outerAngle = 0.0f;
  bool empty() const { return representative < 0; }
};

struct LightTree {
  LightType type = LightType::Point;
  int leafCount = 0;  // a power of two; the tree has 2·leafCount − 1 nodes
  std::vector<LightTreeNode> nodes;
  int firstLeaf() const { return leafCount - 1; }
};

enum class Split { Metric, LongestAxis };

struct TreeOptions {
  Split split = Split::Metric;
  // c of the metric as a fraction of the scene's diagonal (spot lights only). The paper
  // uses the diagonal itself; measured on 65,536 mixed lights (room scene, 320×240, node
  // rule, ε = 0.02), mean cut sizes were 702 at 1, 634 at 1/4, 620 at 1/16 and 584 at 0:
  // the spot bound here is a hard cone test, so compact boxes matter more than narrow
  // cones. (Longest-axis splits: 605.)
  double coneWeight = 0.0;
  std::uint64_t seed = 0x6c69676874637574ull;  // representatives: fixed, so bakes repeat
  // How packLightTrees (bake/light_tree_pack.h) stores node colours.
  NodeColourCoding nodeColour = NodeColourCoding::Rgb9e5;
};

// One tree per light type present, in the order directional, point, spot. Representatives
// are light texture slots of lightOrder(lights).
std::vector<LightTree> buildLightTrees(const std::vector<Light>& lights,
                                       const TreeOptions& options = {});

// Moves the lights `changed` (scene indices) in `trees`, built by buildLightTrees with
// `options` for lights of the same count and types as `lights`, to their values there: each
// one's leaf takes them and every ancestor is merged again from its children. The implicit
// layout and every other node stay. Returns false when a changed light is in no tree, or in
// one of another type (the trees must be built again; `trees` may then be partly refitted);
// lights whose types changed otherwise are not detected here (bake/tree_update.h is).
bool refitLightTrees(std::vector<LightTree>& trees, const std::vector<Light>& lights,
                     const std::vector<int>& changed, const TreeOptions& options = {});

// The paper's cluster metric of a node, with c the scene's diagonal (used for spot cones).
double clusterMetric(const LightTreeNode& node, double c);

}  // namespace manylight
