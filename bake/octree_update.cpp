#include "bake/octree_update.h"

#include <algorithm>

#include "bake/light_support.h"

namespace manylight {

struct DynamicOctree::Visit {
  const octree::Support* support;
  std::uint32_t slot;
  bool add;
};

DynamicOctree::DynamicOctree(const std::vector<Light>& lights, const Scene& scene,
                             OctreeOptions options) {
  options.dynamic = true;
  octree_ = buildLightOctree(lights, scene, options);
  packed_ = packLinklessOctree(octree_);
  margin_ = octree_.margin;
  sceneOfSlot_ = octree_.order;
  slotOfScene_.assign(lights.size(), 0);
  for (std::size_t slot = 0; slot < sceneOfSlot_.size(); ++slot) {
    slotOfScene_[std::size_t(sceneOfSlot_[slot])] = int(slot);
    lights_.push_back(lights[std::size_t(sceneOfSlot_[slot])]);
  }
  inOctree_.assign(lights_.size(), 0);
  for (std::size_t slot = 0; slot < lights_.size(); ++slot)
    inOctree_[slot] = isRanged(lights_[slot]);
  for (std::uint32_t slot : octree_.global) inOctree_[slot] = 0;
  lists_.resize(std::size_t(octree_.levels));
  slot_.resize(std::size_t(octree_.levels));
  for (int level = 0; level < octree_.levels; ++level) {
    const std::vector<OctreeNode>& nodes = octree_.nodes[std::size_t(level)];
    lists_[std::size_t(level)].resize(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      slot_[std::size_t(level)].push_back(linklessSlot(packed_, level, nodes[i].cell));
      if (!nodes[i].leaf) continue;
      const auto first = octree_.indices.begin() + std::ptrdiff_t(nodes[i].first);
      lists_[std::size_t(level)][i].assign(first, first + std::ptrdiff_t(nodes[i].count));
    }
  }
  octree_.indices = {};  // the lists live in lists_ from here on
}

void DynamicOctree::visit(int level, std::size_t index, const Visit& v) {
  const OctreeNode& n = octree_.nodes[std::size_t(level)][index];
  // The build's test for this level: cones against half boxes at the deepest level only.
  const int coneDepth = level == octree_.levels - 1 ? 1 : 0;
  if (level > 0 && !octree::overlaps(*v.support, {n.lo, n.hi}, margin_, coneDepth)) return;
  if (n.leaf) {
    std::vector<std::uint32_t>& list = lists_[std::size_t(level)][index];
    // Lists stay sorted and hold a light once. The tests are the build's, so a removal finds
    // every leaf that lists the light.
    const auto at = std::lower_bound(list.begin(), list.end(), v.slot);
    const bool present = at != list.end() && *at == v.slot;
    if (v.add && !present) list.insert(at, v.slot), ++moved_;
    if (!v.add && present) list.erase(at), ++moved_;
    return;
  }
  std::size_t child = n.firstChild;
  for (int c = 0; c < 8; ++c) {
    if (n.childMask & (1u << c)) visit(level + 1, child++, v);
  }
}

bool DynamicOctree::update(const std::vector<Light>& lights, const std::vector<int>& changed) {
  if (lights.size() != lights_.size()) return false;
  for (int index : changed) {
    const Light& now = lights[std::size_t(index)];
    const Light& before = lights_[std::size_t(slotOfScene_[std::size_t(index)])];
    if (now.type != before.type || isRanged(now) != isRanged(before)) return false;
  }
  moved_ = 0;
  for (int index : changed) {
    const std::uint32_t slot = std::uint32_t(slotOfScene_[std::size_t(index)]);
    const Light& now = lights[std::size_t(index)];
    if (inOctree_[slot]) {
      const octree::Support before = octree::supportOf(lights_[slot]);
      const octree::Support after = octree::supportOf(now);
      visit(0, 0, {&before, slot, false});
      visit(0, 0, {&after, slot, true});
    }
    lights_[slot] = now;
  }
  repack();
  // Lists that grew past the build's bound: the octree must be built again.
  return packed_.indices.size() <= kMaxOctreeIndices;
}

void DynamicOctree::repack() {
  packed_.indices.resize(packed_.globalCount);
  packed_.maxLeafCount = 0;
  for (int level = 0; level < octree_.levels; ++level) {
    const LinklessLevel& l = packed_.level[std::size_t(level)];
    const std::vector<OctreeNode>& nodes = octree_.nodes[std::size_t(level)];
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (!nodes[i].leaf) continue;
      const std::vector<std::uint32_t>& list = lists_[std::size_t(level)][i];
      std::uint32_t* texel =
          &packed_.nodes[2 * (std::size_t(l.nodeBase) + slot_[std::size_t(level)][i])];
      texel[0] = std::uint32_t(packed_.indices.size());
      texel[1] = kOctreeLeafBit | std::uint32_t(list.size());
      packed_.indices.insert(packed_.indices.end(), list.begin(), list.end());
      packed_.maxLeafCount = std::max(packed_.maxLeafCount, std::uint32_t(list.size()));
    }
  }
}

}  // namespace manylight
