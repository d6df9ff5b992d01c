#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace manylight {

View makeView(const Camera& camera, int width, int height) {
  View v;
  v.view = glm::inverse(camera.world);
  v.eye = glm::vec3(camera.world[3]);
  v.forward = glm::normalize(-glm::vec3(camera.world[2]));
  v.orthographic = camera.orthographic;
  const float aspect = float(width) / float(std::max(height, 1));
  if (camera.orthographic) {
    // Keep ymag; widen or narrow x to the image's aspect.
    const float ymag = std::abs(camera.ymag);
    v.projection =
        glm::ortho(-ymag * aspect, ymag * aspect, -ymag, ymag, camera.znear, camera.zfar);
  } else if (camera.zfar > camera.znear) {
    v.projection = glm::perspective(camera.yfov, aspect, camera.znear, camera.zfar);
  } else {
    v.projection = glm::infinitePerspective(camera.yfov, aspect, camera.znear);
  }
  return v;
}

Camera frameBounds(const Bounds& bounds, int width, int height) {
  glm::vec3 centre(0.0f);
  float radius = 1.0f;
  if (!bounds.empty) {
    centre = 0.5f * (bounds.min + bounds.max);
    radius = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
  }
  Camera c;
  c.yfov = glm::radians(45.0f);
  const float aspect = float(width) / float(std::max(height, 1));
  const float xfov = 2.0f * std::atan(std::tan(c.yfov / 2.0f) * aspect);
  const float fov = std::min(c.yfov, xfov);
  const float distance = 1.05f * radius / std::sin(fov / 2.0f);
  const float az = glm::radians(45.0f), el = glm::radians(30.0f);
  const glm::vec3 dir(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  const glm::vec3 eye = centre + dir * distance;
  c.world = glm::inverse(glm::lookAt(eye, centre, glm::vec3(0.0f, 1.0f, 0.0f)));
  c.znear = std::max(distance - 1.5f * radius, distance * 1e-3f);
  c.zfar = distance + 1.5f * radius;
  return c;
}

Camera orbitCamera(const Camera& camera, glm::vec3 centre, float radians) {
  Camera c = camera;
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), centre) *
                         glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0.0f, 1.0f, 0.0f)) *
                         glm::translate(glm::mat4(1.0f), -centre);
  c.world = turn * camera.world;
  return c;
}

std::vector<Light> defaultLightRig(const Camera& camera) {
  struct Rig {
    glm::vec3 towardsLight;  // camera space: +X right, +Y up, +Z towards the viewer
    float lux;
  };
  const Rig rig[] = {
      {{-0.4f, 0.6f, 0.7f}, 1.5f}, {{0.8f, 0.1f, 0.6f}, 0.5f}, {{0.0f, 0.5f, -0.85f}, 0.75f}};
  std::vector<Light> lights;
  for (const Rig& r : rig) {
    Light l;
    l.type = LightType::Directional;
    l.intensity = r.lux;
    l.direction =
        -glm::normalize(glm::vec3(camera.world * glm::vec4(glm::normalize(r.towardsLight), 0.0f)));
    lights.push_back(l);
  }
  return lights;
}

}  // namespace manylight
