#include <random>

#include "generators/scene_builder.h"

namespace manylight {

namespace {

// An 8×8 checker of two colours, sRGB-encoded.
BuilderMaterial checkerMaterial() {
  BuilderMaterial m;
  m.textureWidth = m.textureHeight = 8;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const bool odd = ((x / 2) + (y / 2)) % 2;
      const std::uint8_t c[4] = {std::uint8_t(odd ? 230 : 40), std::uint8_t(odd ? 200 : 90),
                                 std::uint8_t(odd ? 60 : 170), 255};
      m.textureRgba.insert(m.textureRgba.end(), c, c + 4);
    }
  }
  return m;
}

}  // namespace

void writeRoomScene(const std::string& path, const RoomOptions& o) {
  GltfBuilder b;
  BuilderMaterial floor, wall, red, sphere;
  floor.baseColor = {0.75f, 0.75f, 0.72f, 1.0f};
  wall.baseColor = {0.6f, 0.65f, 0.75f, 1.0f};
  red.baseColor = {0.8f, 0.25f, 0.2f, 1.0f};
  sphere.baseColor = {0.9f, 0.9f, 0.9f, 1.0f};
  if (o.specular) {
    sphere.roughness = 0.35f;
    red.metallic = 1.0f;
    red.roughness = 0.5f;
  }
  const int floorM = b.addMaterial(floor), wallM = b.addMaterial(wall), redM = b.addMaterial(red),
            sphereM = b.addMaterial(sphere);
  b.addPlane({0.0f, 0.0f, 0.0f}, {10.0f, 10.0f}, floorM);
  b.addBox({0.0f, 2.5f, -5.0f}, {10.0f, 5.0f, 0.2f}, wallM);
  b.addBox({-1.6f, 0.75f, -0.5f}, {1.5f, 1.5f, 1.5f}, redM, {0.0f, 0.3826834f, 0.0f, 0.9238795f});
  b.addSphere({1.5f, 1.0f, 0.5f}, 2.0f, sphereM);
  if (o.textured) {
    b.addBox({0.0f, 2.0f, -4.8f}, {3.0f, 2.0f, 0.1f}, b.addMaterial(checkerMaterial()));
  }
  b.addPerspectiveCamera({0.0f, 3.0f, 9.0f}, {0.0f, 1.0f, 0.0f}, 0.8f);
  b.addOrthographicCamera({6.0f, 6.0f, 6.0f}, {0.0f, 0.5f, 0.0f}, 6.0f, 6.0f);

  for (const Light& l : o.lights) b.addLight(l);
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float n = float(std::max(o.lightCount, 1));
  for (int i = 0; o.lights.empty() && i < o.lightCount; ++i) {
    Light l;
    l.type = !o.mix ? LightType::Point : LightType(i % 3);
    l.position = {-4.5f + 9.0f * u(rng), 0.3f + 4.0f * u(rng), -4.5f + 9.0f * u(rng)};
    l.colour = glm::vec3(0.3f) + 0.7f * glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec3 target(-3.0f + 6.0f * u(rng), 0.0f, -3.0f + 6.0f * u(rng));
    l.direction = glm::normalize(target - l.position);
    switch (l.type) {
      case LightType::Point:
        l.intensity = (40.0f + 40.0f * u(rng)) / n;
        break;
      case LightType::Spot:
        l.intensity = (80.0f + 80.0f * u(rng)) / n;
        l.outerConeAngle = 0.35f + 0.5f * u(rng);
        l.innerConeAngle = 0.6f * l.outerConeAngle;
        break;
      case LightType::Directional:
        l.direction =
            glm::normalize(glm::vec3(-1.0f + 2.0f * u(rng), -1.0f, -1.0f + 2.0f * u(rng)));
        l.intensity = (1.0f + 2.0f * u(rng)) / n;
        break;
    }
    if (o.withRange && l.type != LightType::Directional && i % 2 == 0)
      l.range = 3.0f + 5.0f * u(rng);
    b.addLight(l);
  }
  b.write(path);
}

std::vector<Light> scatteredLights(int count, bool mixed, std::uint32_t seed, glm::vec3 extent) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Light> lights(std::max(count, 0));
  for (int i = 0; i < count; ++i) {
    Light& l = lights[i];
    l.type = mixed ? LightType(i % 3) : LightType::Point;
    l.position = extent * glm::vec3(u(rng), u(rng), u(rng));
    l.direction = glm::normalize(glm::vec3(u(rng) - 0.5f, -1.0f, u(rng) - 0.5f));
    l.colour = {u(rng), u(rng), u(rng)};
    l.intensity = 0.5f + u(rng);
    l.range = i % 4 == 0 ? 0.0f : 2.0f + 5.0f * u(rng);
    l.outerConeAngle = 0.2f + 0.6f * u(rng);
  }
  return lights;
}

}  // namespace manylight
