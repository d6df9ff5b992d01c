#include <random>

#include "generators/scene_builder.h"

namespace manylight {

namespace {

constexpr float kWallThickness = 0.02f;

}  // namespace

std::vector<CornellWall> cornellWalls() {
  const glm::vec3 white(0.75f), red(0.75f, 0.1f, 0.1f), green(0.1f, 0.75f, 0.1f);
  return {
      {{-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, {0, 1, 0}, white},   // floor, y = 0
      {{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, {0, -1, 0}, white},  // ceiling, y = 2
      {{-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, white},   // back, z = −1
      {{-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, {1, 0, 0}, red},     // left, x = −1
      {{1, 0, -1}, {0, 0, 2}, {0, 2, 0}, {-1, 0, 0}, green},   // right, x = 1
  };
}

Light cornellSpot() {
  Light l;
  l.type = LightType::Spot;
  l.position = {0.0f, 1.9f, 0.0f};
  l.direction = {0.0f, -1.0f, 0.0f};
  l.colour = glm::vec3(1.0f);
  l.intensity = 6.0f;
  l.outerConeAngle = 1.0f;
  l.innerConeAngle = 0.6f;
  return l;
}

void writeCornellScene(const std::string& path, const CornellOptions& o) {
  GltfBuilder b;
  for (const CornellWall& w : cornellWalls()) {
    BuilderMaterial m;
    m.baseColor = glm::vec4(w.albedo, 1.0f);
    const glm::vec3 size = glm::abs(w.u) + glm::abs(w.v) + glm::abs(w.normal) * kWallThickness;
    // The box's inner face lies on the wall: its centre half a thickness behind it.
    const glm::vec3 centre = w.origin + 0.5f * (w.u + w.v) - w.normal * (0.5f * kWallThickness);
    b.addBox(centre, size, b.addMaterial(m));
  }
  if (o.block) {
    BuilderMaterial m;
    m.baseColor = glm::vec4(0.75f, 0.75f, 0.75f, 1.0f);
    b.addBox({0.4f, 0.4f, -0.3f}, {0.5f, 0.8f, 0.5f}, b.addMaterial(m));
  }
  b.addPerspectiveCamera({0.0f, 1.0f, 3.4f}, {0.0f, 1.0f, 0.0f}, 0.75f);
  b.addLight(cornellSpot());
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float n = float(std::max(o.extraLights, 1));
  for (int i = 0; i < o.extraLights; ++i) {
    Light l;
    l.type = LightType(i % 3);
    l.position = glm::vec3(-0.9f, 0.1f, -0.9f) + 1.8f * glm::vec3(u(rng), u(rng), u(rng));
    l.direction = glm::normalize(glm::vec3(u(rng) - 0.5f, -1.0f, u(rng) - 0.5f));
    l.colour = glm::vec3(0.4f) + 0.6f * glm::vec3(u(rng), u(rng), u(rng));
    l.intensity = (l.type == LightType::Directional ? 0.3f : 3.0f) * (0.5f + u(rng)) / n;
    l.outerConeAngle = 0.3f + 0.6f * u(rng);
    l.innerConeAngle = 0.5f * l.outerConeAngle;
    if (l.type != LightType::Directional && i % 2 == 0) l.range = 0.8f + 1.5f * u(rng);
    b.addLight(l);
  }
  b.write(path);
}

}  // namespace manylight
