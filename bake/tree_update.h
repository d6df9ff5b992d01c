#pragma once
// Light trees whose lights move (playback of animated lights): the trees of bake/light_tree.h
// kept unpacked and refitted in place (refitLightTrees), then packed again.
#include <vector>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"

namespace manylight {

class DynamicTrees {
 public:
  // The trees of `lights`, built with `options`.
  DynamicTrees(const std::vector<Light>& lights, const TreeOptions& options);

  // Moves the lights `changed` (scene indices) to their values in `lights`. Returns false
  // when the trees cannot hold them where they are (a light changed type, or the count
  // changed): the caller builds new ones.
  bool update(const std::vector<Light>& lights, const std::vector<int>& changed);

  // The trees packed as they stand.
  PackedTrees packed() const { return packLightTrees(trees_, options_.nodeColour); }

 private:
  TreeOptions options_;
  std::vector<LightTree> trees_;
  std::vector<LightType> types_;  // per scene light, as built
};

}  // namespace manylight
