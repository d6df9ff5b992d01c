#include "bake/light_pack.h"

#include <algorithm>
#include <cmath>

#include "bake/light_texture_layout.h"
#include "scene/shading_model.h"

namespace manylight {

LightOrder lightOrder(const std::vector<Light>& lights) {
  LightOrder order;
  order.scene.reserve(lights.size());
  for (LightType type : {LightType::Directional, LightType::Point, LightType::Spot}) {
    if (type == LightType::Point) order.pointStart = int(order.scene.size());
    if (type == LightType::Spot) order.spotStart = int(order.scene.size());
    for (std::size_t i = 0; i < lights.size(); ++i) {
      if (lights[i].type == type) order.scene.push_back(int(i));
    }
  }
  return order;
}

SpotConeTerms spotConeTerms(const Light& l) {
  if (l.type != LightType::Spot) return {};
  const double cosOuter = std::cos(double(l.outerConeAngle));
  const double cosInner = std::cos(double(l.innerConeAngle));
  const double s = 1.0 / std::max(cosInner - cosOuter, shading::kMinConeWidth);
  return {float(s), float(-cosOuter * s)};
}

PackedLights packLights(const std::vector<Light>& lights) {
  PackedLights packed;
  const LightOrder order = lightOrder(lights);
  packed.pointStart = order.pointStart;
  packed.spotStart = order.spotStart;
  packed.texels = packLightTexels(lights, order.scene);
  return packed;
}

std::vector<float> packLightTexels(const std::vector<Light>& lights,
                                   const std::vector<int>& order) {
  std::vector<float> out(order.size() * layout::kFloatsPerLight, 0.0f);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Light& l = lights[std::size_t(order[i])];
    float* t = &out[i * layout::kFloatsPerLight];
    const glm::vec3 radiant = l.colour * l.intensity;
    if (l.type == LightType::Directional) {
      t[0] = -l.direction.x, t[1] = -l.direction.y, t[2] = -l.direction.z;
      t[3] = layout::kDirectionalMarker;
    } else {
      t[0] = l.position.x, t[1] = l.position.y, t[2] = l.position.z;
      t[3] = l.range > 0.0f && std::isfinite(l.range) ? 1.0f / (l.range * l.range) : 0.0f;
    }
    if (l.type == LightType::Spot) t[4] = l.direction.x, t[5] = l.direction.y, t[6] = l.direction.z;
    const SpotConeTerms cone = spotConeTerms(l);
    t[7] = cone.scale;
    t[8] = radiant.r, t[9] = radiant.g, t[10] = radiant.b;
    t[11] = cone.offset;
  }
  return out;
}

}  // namespace manylight
