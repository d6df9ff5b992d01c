#pragma once
// A light octree whose lights move (playback of animated lights): the octree keeps its
// cells, and a moved light leaves the lists of the leaves its old support overlapped and
// joins those its new support overlaps, found by descending only where the supports reach.
// The linkless octree's leaf texels and index list are then rewritten from the lists; its
// hash tables stay, since no node comes or goes. Exact as a rebuild is: a leaf lists every
// light whose support overlaps it. Tightness can drop where lights move into cells that were
// coarse leaves when it was built; update() says when a rebuild would pay.
#include <cstdint>
#include <vector>

#include "bake/light_octree.h"
#include "bake/linkless_octree.h"

namespace manylight {

class DynamicOctree {
 public:
  // The octree of `lights` over `scene`, built with OctreeOptions::dynamic.
  DynamicOctree(const std::vector<Light>& lights, const Scene& scene, OctreeOptions options = {});

  // Moves the lights `changed` (scene indices) to their values in `lights`. Returns false
  // when the caller must build a new octree: a changed light cannot stay where it is in the
  // octree's order (it gained or lost a range, or changed type; nothing was changed), or the
  // lists grew past kMaxOctreeIndices (they were changed).
  bool update(const std::vector<Light>& lights, const std::vector<int>& changed);

  const LinklessOctree& packed() const { return packed_; }
  // List entries written by the last update (for statistics).
  std::size_t entriesMoved() const { return moved_; }

 private:
  struct Visit;
  void visit(int level, std::size_t index, const Visit& v);
  void repack();

  LightOctree octree_;  // its cells (its lists are in lists_)
  LinklessOctree packed_;
  float margin_ = 0.0f;
  std::vector<int> sceneOfSlot_, slotOfScene_;
  std::vector<char> inOctree_;  // per slot
  std::vector<Light> lights_;   // per slot, as last placed
  // Per level, per node: its leaf list (leaves only) and its slot in the level's table.
  std::vector<std::vector<std::vector<std::uint32_t>>> lists_;
  std::vector<std::vector<std::uint32_t>> slot_;
  std::size_t moved_ = 0;
};

}  // namespace manylight
