#include "bake/linkless_octree.h"

#include <algorithm>

#include "bake/spatial_hash.h"
#include "base/parallel.h"

namespace manylight {

std::size_t LinklessOctree::bytes() const {
  return nodes.size() * 4 + offsets.size() * 2 + indices.size() * 4;
}

LinklessOctree packLinklessOctree(const LightOctree& octree) {
  LinklessOctree out;
  out.origin = octree.origin;
  out.leafEdge = octree.leafEdge;
  out.levels = octree.levels;
  out.globalCount = std::uint32_t(octree.global.size());
  out.maxLeafCount = octree.maxLeafCount;
  out.wholeScene = octree.wholeScene;
  out.order = octree.order;
  out.unreached = octree.unreached.size();
  out.indices.reserve(octree.global.size() + octree.indices.size());
  out.indices = octree.global;
  out.indices.insert(out.indices.end(), octree.indices.begin(), octree.indices.end());

  // The levels' hashes are independent: built on two threads, deepest (largest) first.
  std::vector<SpatialHash> hashes(std::size_t(octree.levels));
  auto hashLevel = [&](int level) {
    const std::vector<OctreeNode>& nodes = octree.nodes[std::size_t(level)];
    std::vector<glm::uvec3> keys(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) keys[i] = nodes[i].cell;
    hashes[std::size_t(level)] = buildSpatialHash(keys);
  };
  runOnThreads(2, [&](int half) {
    for (int level = octree.levels - 1 - half; level >= 0; level -= 2) hashLevel(level);
  });

  out.level.resize(std::size_t(octree.levels));
  for (int level = 0; level < octree.levels; ++level) {
    const SpatialHash& h = hashes[std::size_t(level)];
    const std::vector<OctreeNode>& nodes = octree.nodes[std::size_t(level)];
    LinklessLevel& l = out.level[std::size_t(level)];
    l.dims = h.dims;
    l.nodeBase = int(out.nodes.size() / 2);
    l.offsetBase = int(out.offsets.size() / 4);
    l.offsetCount = h.offsetCount;
    l.nodeCount = int(nodes.size());
    l.attempts = h.attempts;
    out.nodes.resize(out.nodes.size() + 2 * h.slotCount(), 0u);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const OctreeNode& n = nodes[i];
      std::uint32_t* texel = &out.nodes[2 * (std::size_t(l.nodeBase) + h.slots[i])];
      texel[0] = n.leaf ? n.first + out.globalCount : 0u;
      texel[1] = n.leaf ? (kOctreeLeafBit | n.count) : n.childMask;
    }
    const std::vector<std::uint16_t> offsets = spatialHashTexels(h);
    out.offsets.insert(out.offsets.end(), offsets.begin(), offsets.end());
  }
  return out;
}

OctreeSummary summarise(const LinklessOctree& o) {
  OctreeSummary s;
  s.built = true;
  s.levels = o.levels;
  s.leafEdge = o.leafEdge;
  for (const LinklessLevel& l : o.level) {
    s.nodes += std::size_t(l.nodeCount);
    s.offsetEntries += std::size_t(l.offsetCount);
    s.hashAttempts += l.attempts;
  }
  s.slots = o.nodes.size() / 2;
  s.indices = o.indices.size();
  s.bytes = o.bytes();
  s.globalCount = o.globalCount;
  s.maxLeafCount = o.maxLeafCount;
  s.wholeScene = o.wholeScene;
  s.unreached = o.unreached;
  return s;
}

namespace {

// hashSlot of bake/spatial_hash.h from the packed offset table.
std::uint32_t packedSlot(const LinklessOctree& o, const LinklessLevel& l, glm::uvec3 key) {
  SpatialHash h;
  h.dims = l.dims;
  h.offsetCount = l.offsetCount;
  const std::uint32_t entry = spatialHashEntry(h, key);
  const std::uint16_t* t = &o.offsets[4 * (std::size_t(l.offsetBase) + entry)];
  const glm::uvec3 dims(l.dims);
  const glm::uvec3 s = (key + glm::uvec3(t[0], t[1], t[2])) % dims;
  return s.x + dims.x * (s.y + dims.y * s.z);
}

}  // namespace

std::uint32_t linklessSlot(const LinklessOctree& o, int level, glm::uvec3 key) {
  return packedSlot(o, o.level[std::size_t(level)], key);
}

OctreeList linklessListAt(const LinklessOctree& o, glm::vec3 p) {
  const int deepest = o.levels - 1;
  const float cells = float(1u << deepest);
  const glm::uvec3 cell(glm::clamp(glm::floor((p - o.origin) / o.leafEdge), glm::vec3(0.0f),
                                   glm::vec3(cells - 1.0f)));
  glm::uvec3 key(0u);
  for (int level = 0;; ++level) {
    const LinklessLevel& l = o.level[std::size_t(level)];
    const std::uint32_t* texel = &o.nodes[2 * (std::size_t(l.nodeBase) + packedSlot(o, l, key))];
    if (texel[1] & kOctreeLeafBit) return {texel[0], texel[1] & ~kOctreeLeafBit};
    key = cell >> std::uint32_t(deepest - level - 1);
    const glm::uvec3 c = key & 1u;
    if (!(texel[1] & (1u << (c.x + 2 * c.y + 4 * c.z)))) return {0, 0};
  }
}

}  // namespace manylight
