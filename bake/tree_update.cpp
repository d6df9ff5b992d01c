#include "bake/tree_update.h"

namespace manylight {

DynamicTrees::DynamicTrees(const std::vector<Light>& lights, const TreeOptions& options)
    : options_(options), trees_(buildLightTrees(lights, options)) {
  for (const Light& l : lights) types_.push_back(l.type);
}

bool DynamicTrees::update(const std::vector<Light>& lights, const std::vector<int>& changed) {
  if (lights.size() != types_.size()) return false;
  for (int index : changed) {
    if (lights[std::size_t(index)].type != types_[std::size_t(index)]) return false;
  }
  return refitLightTrees(trees_, lights, changed, options_);
}

}  // namespace manylight
