#include "bake/baked_octree.h"

#include <cmath>

namespace manylight::baked {

void writeOctree(Writer& w, const LinklessOctree& o) {
  w.put(o.origin);
  w.put(o.leafEdge);
  w.put(std::uint32_t(o.levels));
  for (const LinklessLevel& l : o.level) {
    w.put(l.dims);
    w.put(std::int32_t(l.nodeBase)), w.put(std::int32_t(l.offsetBase));
    w.put(std::int32_t(l.offsetCount)), w.put(std::int32_t(l.nodeCount));
    w.put(std::int32_t(l.attempts));
  }
  w.array(o.nodes);
  w.array(o.offsets);
  w.array(o.indices);
  w.array(o.order);
  w.put(o.globalCount);
  w.put(o.maxLeafCount);
  w.array(o.wholeScene);
  w.put(std::uint64_t(o.unreached));
}

namespace {

void checkLevels(Reader& r, const LinklessOctree& o) {
  std::size_t nodeTexels = 0, offsetTexels = 0;
  for (const LinklessLevel& l : o.level) {
    if (l.dims.x < 1 || l.dims.y < 1 || l.dims.z < 1 || l.dims.x > 65536 || l.dims.y > 65536 ||
        l.dims.z > 65536)
      r.fail("a level's hash table extent is out of range");
    const std::size_t slots = std::size_t(l.dims.x) * std::size_t(l.dims.y) * std::size_t(l.dims.z);
    if (std::size_t(l.nodeBase) != nodeTexels || std::size_t(l.offsetBase) != offsetTexels ||
        l.offsetCount < 1 || l.nodeCount < 0 || std::size_t(l.nodeCount) > slots)
      r.fail("the levels' tables do not add up");
    nodeTexels += slots;
    offsetTexels += std::size_t(l.offsetCount);
  }
  if (nodeTexels * 2 != o.nodes.size() || offsetTexels * 4 != o.offsets.size())
    r.fail("the levels' tables do not add up");
  for (const LinklessLevel& l : o.level) {
    for (int i = 0; i < l.offsetCount; ++i) {
      const std::uint16_t* t = &o.offsets[4 * (std::size_t(l.offsetBase) + std::size_t(i))];
      if (t[0] >= l.dims.x || t[1] >= l.dims.y || t[2] >= l.dims.z)
        r.fail("a hash offset lies outside its table");
    }
  }
}

void checkLists(Reader& r, const LinklessOctree& o, std::size_t lights) {
  if (o.globalCount > o.indices.size()) r.fail("the global list runs past the index list");
  for (std::size_t t = 0; t < o.nodes.size(); t += 2) {
    if (!(o.nodes[t + 1] & kOctreeLeafBit)) continue;
    const std::uint64_t count = o.nodes[t + 1] & ~kOctreeLeafBit;
    if (std::uint64_t(o.nodes[t]) + count > o.indices.size() || count > o.maxLeafCount)
      r.fail("a leaf's list runs past the index list");
  }
  std::vector<char> seen(lights, 0);
  if (o.order.size() != lights) r.fail("the light order does not hold every light");
  for (int index : o.order) {
    if (index < 0 || std::size_t(index) >= lights || seen[std::size_t(index)])
      r.fail("the light order does not hold every light once");
    seen[std::size_t(index)] = 1;
  }
  for (std::uint32_t index : o.indices) {
    if (index >= lights)
      r.fail("a list names light " + std::to_string(index) + " of " + std::to_string(lights));
  }
  for (int index : o.wholeScene) {
    if (index < 0 || std::size_t(index) >= lights) r.fail("a whole-scene light does not exist");
  }
}

}  // namespace

LinklessOctree readOctree(Reader& r, std::size_t lights) {
  LinklessOctree o;
  o.origin = r.get<glm::vec3>();
  o.leafEdge = r.get<float>();
  if (!std::isfinite(o.origin.x + o.origin.y + o.origin.z) || !(o.leafEdge > 0.0f) ||
      !std::isfinite(o.leafEdge))
    r.fail("the octree's origin or leaf edge is not finite");
  o.levels = int(r.count(std::uint32_t(kMaxOctreeLevels), "octree levels"));
  if (o.levels < 1) r.fail("an octree has at least one level");
  o.level.resize(std::size_t(o.levels));
  for (LinklessLevel& l : o.level) {
    l.dims = r.get<glm::ivec3>();
    l.nodeBase = r.get<std::int32_t>(), l.offsetBase = r.get<std::int32_t>();
    l.offsetCount = r.get<std::int32_t>(), l.nodeCount = r.get<std::int32_t>();
    l.attempts = r.get<std::int32_t>();
  }
  o.nodes = r.array<std::uint32_t>();
  o.offsets = r.array<std::uint16_t>();
  o.indices = r.array<std::uint32_t>();
  o.order = r.array<int>();
  o.globalCount = r.get<std::uint32_t>();
  o.maxLeafCount = r.get<std::uint32_t>();
  o.wholeScene = r.array<int>();
  o.unreached = std::size_t(r.get<std::uint64_t>());
  checkLevels(r, o);
  checkLists(r, o, lights);
  return o;
}

}  // namespace manylight::baked
