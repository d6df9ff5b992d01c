#include "scene/gltf_attributes.h"

#include <tiny_gltf.h>

#include "scene/gltf_accessors.h"
#include "scene/gltf_draco.h"

namespace manylight::gltf {

AttributeSource::AttributeSource(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                 const std::string& where)
    : model_(model), primitive_(primitive) {
  if (hasDraco(primitive)) draco_ = std::make_unique<DracoPrimitive>(model, primitive, where);
}

AttributeSource::~AttributeSource() = default;

int AttributeSource::accessor(const std::string& name) const {
  const auto it = primitive_.attributes.find(name);
  return it == primitive_.attributes.end() ? -1 : it->second;
}

std::vector<float> AttributeSource::floats(const std::string& name, int components) const {
  if (draco_ && draco_->has(name)) return draco_->floats(name, components);
  return readFloats(model_, accessor(name), components, name);
}

bool AttributeSource::hasIndices() const { return draco_ || primitive_.indices >= 0; }

std::vector<std::uint32_t> AttributeSource::indices() const {
  if (draco_) return draco_->indices();
  return readIndices(model_, primitive_.indices);
}

}  // namespace manylight::gltf
