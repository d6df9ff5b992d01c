#include "generators/light_layouts.h"

#include <cmath>
#include <random>

#include "base/error.h"
#include "scene/srgb.h"

namespace manylight {

const std::vector<std::pair<LightLayout, std::string>>& lightLayoutNames() {
  static const std::vector<std::pair<LightLayout, std::string>> names = {
      {LightLayout::Uniform, "uniform"},
      {LightLayout::Clustered, "clustered"},
      {LightLayout::Street, "street"},
      {LightLayout::Mixed, "mixed"},
      {LightLayout::Coincident, "coincident"},
      {LightLayout::TwoGroups, "two-groups"},
      {LightLayout::WideIntensities, "wide-intensities"},
      {LightLayout::BrightAmongDim, "bright-among-dim"},
      {LightLayout::Far, "far"},
      {LightLayout::SpotsAway, "spots-away"},
      {LightLayout::OnSurfaces, "on-surfaces"},
      {LightLayout::EightBitColours, "eight-bit-colours"},
      {LightLayout::UniformRanged, "uniform-ranged"},
      {LightLayout::StreetRanged, "street-ranged"},
  };
  return names;
}

const std::string& lightLayoutName(LightLayout layout) {
  for (const auto& [l, name] : lightLayoutNames())
    if (l == layout) return name;
  return lightLayoutNames().front().second;
}

LightLayout parseLightLayout(const std::string& name) {
  std::string choices;
  for (const auto& [layout, n] : lightLayoutNames()) {
    if (n == name) return layout;
    choices += (choices.empty() ? "" : ", ") + n;
  }
  throw Error("unknown light layout '" + name + "' (choose from " + choices + ")");
}

namespace {

// The ranged layouts' light i of `count`, drawing from `u` and `rng`.
void placeRanged(Light& l, LightLayout layout, int i, int count, std::mt19937& rng,
                 std::uniform_real_distribution<float>& u) {
  if (layout == LightLayout::UniformRanged) {
    // kRangedReach = count / volume · 4/3 π r³ over the room's 9 × 4 × 9 m.
    const float r = float(std::cbrt(3.0 * 324.0 * kRangedReach / (4.0 * 3.14159265 * count)));
    l.range = r;
    l.intensity = 0.04f * r * r;  // irradiance about 2 on the walls, whatever the count
    return;
  }
  // A lamp at height r/2 lights a disc of radius r/2 · tan 0.9 ≈ 0.63 r of the floor:
  // kRangedReach = count / 81 m² · π (0.63 r)².
  const float r = float(std::sqrt(kRangedReach * 81.0 / (1.25 * count)));
  const int side = std::max(1, int(std::ceil(std::sqrt(double(count)))));
  const glm::vec2 cell(float(i % side) + u(rng), float(i / side) + u(rng));
  l.type = LightType::Spot;
  l.position =
      glm::vec3(-4.5f + 9.0f * cell.x / float(side), 0.5f * r, -4.5f + 9.0f * cell.y / float(side));
  l.direction = {0.0f, -1.0f, 0.0f};
  l.outerConeAngle = 0.9f;
  l.innerConeAngle = 0.5f;
  l.range = r;
  l.colour = {1.0f, 0.75f, 0.45f};
  l.intensity = 0.01f * r * r;  // irradiance about 2 on the floor, whatever the count
}

}  // namespace

std::vector<Light> layoutLights(LightLayout layout, int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto inRoom = [&] {
    return glm::vec3(-4.5f + 9.0f * u(rng), 0.3f + 4.0f * u(rng), -4.5f + 9.0f * u(rng));
  };
  std::vector<glm::vec3> centres;
  for (int k = 0; k < 12; ++k) centres.push_back(inRoom());
  const glm::vec3 corners[2] = {{-4.0f, 0.8f, -4.0f}, {4.0f, 3.8f, 4.0f}};
  std::vector<Light> lights(std::size_t(std::max(count, 0)));
  for (int i = 0; i < count; ++i) {
    Light& l = lights[std::size_t(i)];
    l.colour = glm::vec3(0.3f) + 0.7f * glm::vec3(u(rng), u(rng), u(rng));
    l.intensity = 60.0f / float(count);
    l.position = inRoom();
    auto jitter = [&](float size) {
      return size * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
    };
    switch (layout) {
      case LightLayout::Uniform:
        break;
      case LightLayout::Clustered:
        l.position = centres[std::size_t(i) % centres.size()] + jitter(0.05f);
        break;
      case LightLayout::Street: {
        // Evenly along x, in order, a little jitter so no two coincide.
        const float t = count > 1 ? float(i) / float(count - 1) : 0.5f;
        l.type = LightType::Spot;
        l.position = glm::vec3(-4.5f + 9.0f * t, 4.0f, 0.0f) + jitter(0.01f);
        l.direction = {0.0f, -1.0f, 0.0f};
        l.outerConeAngle = 0.9f;
        l.innerConeAngle = 0.5f;
        l.range = 6.0f;
        l.colour = {1.0f, 0.75f, 0.45f};  // sodium-ish
        l.intensity = 120.0f / float(count);
        break;
      }
      case LightLayout::Coincident:
        l.position = {0.5f, 2.5f, 1.0f};
        break;
      case LightLayout::TwoGroups:
        l.position = corners[i % 2] + jitter(0.05f);
        break;
      case LightLayout::WideIntensities:
        l.intensity = std::pow(10.0f, -6.0f + 12.0f * u(rng)) / float(count);
        break;
      case LightLayout::BrightAmongDim:
        l.intensity = count > 1 ? (i == 0 ? 30.0f : 30.0f / float(count - 1)) : 30.0f;
        break;
      case LightLayout::Far: {
        const glm::vec3 d = glm::normalize(glm::vec3(u(rng) - 0.5f, 0.2f + u(rng), u(rng) - 0.5f));
        l.position = 1e5f * d + glm::vec3(u(rng), u(rng), u(rng));
        l.intensity = 60.0f * 1e10f / float(count);
        break;
      }
      case LightLayout::SpotsAway:
        l.type = LightType::Spot;
        l.direction = glm::normalize(glm::vec3(u(rng) - 0.5f, 4.0f, u(rng) - 0.5f));
        l.outerConeAngle = 0.2f + 0.4f * u(rng);
        l.innerConeAngle = 0.5f * l.outerConeAngle;
        break;
      case LightLayout::OnSurfaces:
        // Half on the floor (y = 0), half on the back wall (z = −5): shading points sit
        // inside the boxes of clusters down to a few lights.
        if (i % 2 == 0) {
          l.position = glm::vec3(-4.5f + 9.0f * u(rng), 0.001f, -4.5f + 9.0f * u(rng));
        } else {
          l.position = glm::vec3(-4.5f + 9.0f * u(rng), 0.3f + 4.0f * u(rng),
                                 -4.899f);  // the wall's face is at z = −4.9
        }
        break;
      case LightLayout::EightBitColours: {
        // As a light list gives them: 8-bit sRGB codes, often saturated, decoded exactly.
        std::uniform_int_distribution<int> code(0, 255);
        for (int c = 0; c < 3; ++c)
          l.colour[c] = float(decodeSrgb8(std::uint8_t(i % 4 == c ? 0 : code(rng))));
        break;
      }
      case LightLayout::UniformRanged:
      case LightLayout::StreetRanged:
        placeRanged(l, layout, i, count, rng, u);
        break;
      case LightLayout::Mixed:
        l.type = LightType(i % 3);
        l.direction = glm::normalize(glm::vec3(-3.0f + 6.0f * u(rng), 0.0f, -3.0f + 6.0f * u(rng)) -
                                     l.position);
        if (l.type == LightType::Spot) {
          l.outerConeAngle = 0.35f + 0.5f * u(rng);
          l.innerConeAngle = 0.6f * l.outerConeAngle;
          l.intensity *= 2.0f;
        }
        if (l.type == LightType::Directional) l.intensity = 1.0f / float(count);
        if (l.type != LightType::Directional && i % 2 == 0) l.range = 3.0f + 5.0f * u(rng);
        break;
    }
  }
  return lights;
}

}  // namespace manylight
