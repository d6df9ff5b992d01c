#include "bake/light_pack.h"

#include <algorithm>
#include <cmath>

#include "bake/light_texture_layout.h"
#include "scene/shading_model.h"

namespace manylight {

PackedLights packLights(const std::vector<Light>& lights) {
  PackedLights packed;
  std::vector<const Light*> order;
  order.reserve(lights.size());
  for (LightType type : {LightType::Directional, LightType::Point, LightType::Spot}) {
    if (type == LightType::Point) packed.pointStart = int(order.size());
    if (type == LightType::Spot) packed.spotStart = int(order.size());
    for (const Light& l : lights) {
      if (l.type == type) order.push_back(&l);
    }
  }
  std::vector<float>& out = packed.texels;
  out.assign(lights.size() * layout::kFloatsPerLight, 0.0f);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Light& l = *order[i];
    float* t = &out[i * layout::kFloatsPerLight];
    const glm::vec3 radiant = l.colour * l.intensity;
    if (l.type == LightType::Directional) {
      t[0] = -l.direction.x, t[1] = -l.direction.y, t[2] = -l.direction.z;
      t[3] = layout::kDirectionalMarker;
    } else {
      t[0] = l.position.x, t[1] = l.position.y, t[2] = l.position.z;
      t[3] = l.range > 0.0f && std::isfinite(l.range) ? 1.0f / (l.range * l.range) : 0.0f;
    }
    float scale = 0.0f, offset = 1.0f;
    if (l.type == LightType::Spot) {
      const double cosOuter = std::cos(double(l.outerConeAngle));
      const double cosInner = std::cos(double(l.innerConeAngle));
      const double s = 1.0 / std::max(cosInner - cosOuter, shading::kMinConeWidth);
      scale = float(s);
      offset = float(-cosOuter * s);
      t[4] = l.direction.x, t[5] = l.direction.y, t[6] = l.direction.z;
    }
    t[7] = scale;
    t[8] = radiant.r, t[9] = radiant.g, t[10] = radiant.b;
    t[11] = offset;
  }
  return packed;
}

}  // namespace manylight
