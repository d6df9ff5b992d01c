#include "bake/light_pack.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "bake/light_texture_layout.h"
#include "base/parallel.h"
#include "scene/shading_model.h"

namespace manylight {

// Fewer lights than this a thread are ordered or packed on one.
constexpr std::size_t kLightsPerThread = 65536;

// A counting sort, stable, in shares: each share counts its lights' types, then places them
// after the earlier shares' lights of each type.
LightOrder lightOrder(const std::vector<Light>& lights) {
  const auto rank = [](LightType t) {
    return t == LightType::Directional ? 0 : t == LightType::Point ? 1 : 2;
  };
  const int shares = sharesOf(lights.size(), kLightsPerThread);
  std::vector<std::array<std::size_t, 3>> counts(std::size_t(shares), {0, 0, 0});
  runOnShares(shares, lights.size(), [&](int k, std::size_t from, std::size_t to) {
    std::array<std::size_t, 3> c = {0, 0, 0};  // local: the shares' counts share a cache line
    for (std::size_t i = from; i < to; ++i) ++c[rank(lights[i].type)];
    counts[std::size_t(k)] = c;
  });
  std::size_t total[3] = {0, 0, 0};
  for (const auto& c : counts) {
    for (int t = 0; t < 3; ++t) total[t] += c[t];
  }
  LightOrder order;
  order.pointStart = int(total[0]);
  order.spotStart = int(total[0] + total[1]);
  order.scene.resize(lights.size());
  std::size_t next[3] = {0, total[0], total[0] + total[1]};
  for (auto& c : counts) {  // each share's first slot of each type
    for (int t = 0; t < 3; ++t) {
      const std::size_t n = c[t];
      c[t] = next[t];
      next[t] += n;
    }
  }
  runOnShares(shares, lights.size(), [&](int k, std::size_t from, std::size_t to) {
    std::array<std::size_t, 3> at = counts[std::size_t(k)];
    for (std::size_t i = from; i < to; ++i) order.scene[at[rank(lights[i].type)]++] = int(i);
  });
  return order;
}

SpotConeTerms spotConeTerms(const Light& l) {
  if (l.type != LightType::Spot) return {};
  const double cosOuter = std::cos(double(l.outerConeAngle));
  const double cosInner = std::cos(double(l.innerConeAngle));
  const double s = 1.0 / std::max(cosInner - cosOuter, shading::kMinConeWidth);
  return {float(s), float(-cosOuter * s)};
}

namespace {

// One light's texels at `t` (bake/light_texture_layout.h).
void packLightTexel(const Light& l, float* t) {
  const glm::vec3 radiant = l.colour * l.intensity;
  if (l.type == LightType::Directional) {
    t[0] = -l.direction.x, t[1] = -l.direction.y, t[2] = -l.direction.z;
    t[3] = layout::kDirectionalMarker;
  } else {
    t[0] = l.position.x, t[1] = l.position.y, t[2] = l.position.z;
    t[3] = l.range > 0.0f && std::isfinite(l.range) ? 1.0f / (l.range * l.range) : 0.0f;
  }
  const glm::vec3 axis = l.type == LightType::Spot ? l.direction : glm::vec3(0.0f);
  t[4] = axis.x, t[5] = axis.y, t[6] = axis.z;
  const SpotConeTerms cone = spotConeTerms(l);
  t[7] = cone.scale;
  t[8] = radiant.r, t[9] = radiant.g, t[10] = radiant.b;
  t[11] = cone.offset;
}

}  // namespace

PackedLights packLights(const std::vector<Light>& lights) {
  PackedLights packed;
  const LightOrder order = lightOrder(lights);
  packed.pointStart = order.pointStart;
  packed.spotStart = order.spotStart;
  packed.texels = packLightTexels(lights, order.scene);
  return packed;
}

UninitialisedVector<float> packLightTexels(const std::vector<Light>& lights,
                                           const std::vector<int>& order) {
  UninitialisedVector<float> out(order.size() * layout::kFloatsPerLight);  // written whole below
  runOnShares(sharesOf(order.size(), kLightsPerThread), order.size(),
              [&](int, std::size_t from, std::size_t to) {
                for (std::size_t i = from; i < to; ++i)
                  packLightTexel(lights[std::size_t(order[i])], &out[i * layout::kFloatsPerLight]);
              });
  return out;
}

}  // namespace manylight
