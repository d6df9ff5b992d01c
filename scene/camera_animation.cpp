#include "scene/camera_animation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/gltf_convert.h"

namespace manylight {
namespace {

int components(const AnimationTrack& t) { return t.path == AnimationTrack::Rotation ? 4 : 3; }

glm::vec4 key(const AnimationTrack& t, std::size_t k,
              int part) {  // part: 0 in-tangent, 1 value, 2 out-tangent
  const int n = components(t);
  const std::size_t stride = t.interpolation == AnimationTrack::CubicSpline ? 3 : 1;
  const std::size_t at = (k * stride + (stride == 3 ? std::size_t(part) : 0)) * std::size_t(n);
  glm::vec4 v(0.0f);
  for (int c = 0; c < n; ++c) v[c] = t.values[at + std::size_t(c)];
  return v;
}

glm::vec4 sample(const AnimationTrack& t, float seconds) {
  const std::size_t keys = t.times.size();
  if (seconds <= t.times.front() || keys == 1) return key(t, 0, 1);
  if (seconds >= t.times.back()) return key(t, keys - 1, 1);
  const std::size_t k1 =
      std::size_t(std::upper_bound(t.times.begin(), t.times.end(), seconds) - t.times.begin());
  const std::size_t k0 = k1 - 1;
  const float dt = t.times[k1] - t.times[k0];
  const float u = (seconds - t.times[k0]) / dt;
  switch (t.interpolation) {
    case AnimationTrack::Step:
      return key(t, k0, 1);
    case AnimationTrack::CubicSpline: {
      const float u2 = u * u, u3 = u2 * u;
      const glm::vec4 v = (2 * u3 - 3 * u2 + 1) * key(t, k0, 1) +
                          dt * (u3 - 2 * u2 + u) * key(t, k0, 2) +
                          (-2 * u3 + 3 * u2) * key(t, k1, 1) + dt * (u3 - u2) * key(t, k1, 0);
      return v;
    }
    default:
      if (t.path == AnimationTrack::Rotation) {
        const glm::vec4 a = key(t, k0, 1), b = key(t, k1, 1);
        const glm::quat q =
            glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), u);
        return {q.x, q.y, q.z, q.w};
      }
      return glm::mix(key(t, k0, 1), key(t, k1, 1), u);
  }
}

glm::mat4 local(const AnimatedNode& n, float seconds) {
  if (n.hasMatrix) return n.matrix;
  glm::vec3 translation = n.translation, scale = n.scale;
  glm::vec4 rotation = n.rotation;
  for (const AnimationTrack& t : n.tracks) {
    const glm::vec4 v = sample(t, seconds);
    if (t.path == AnimationTrack::Translation) translation = glm::vec3(v);
    if (t.path == AnimationTrack::Rotation) rotation = v;
    if (t.path == AnimationTrack::Scale) scale = glm::vec3(v);
  }
  glm::quat q(rotation.w, rotation.x, rotation.y, rotation.z);
  const float len = glm::length(q);
  q = len > 0.0f ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(q) *
         glm::scale(glm::mat4(1.0f), scale);
}

}  // namespace

glm::mat4 animatedCameraWorld(const Camera& camera, float seconds) {
  if (camera.animation.chain.empty()) return camera.world;
  glm::mat4 world(1.0f);
  for (const AnimatedNode& n : camera.animation.chain) world = world * local(n, seconds);
  return gltf::withoutScale(world);
}

std::string checkTrack(const AnimationTrack& t) {
  if (t.times.empty()) return "no keys";
  for (std::size_t k = 0; k < t.times.size(); ++k) {
    if (!std::isfinite(t.times[k]) || t.times[k] < 0.0f) return "key times must be finite and >= 0";
    if (k > 0 && !(t.times[k] > t.times[k - 1])) return "key times must increase";
  }
  const std::size_t per =
      std::size_t(components(t)) * (t.interpolation == AnimationTrack::CubicSpline ? 3 : 1);
  if (t.values.size() != t.times.size() * per) {
    return std::to_string(t.values.size()) + " values for " + std::to_string(t.times.size()) +
           " keys, expected " + std::to_string(t.times.size() * per);
  }
  for (float v : t.values) {
    if (!std::isfinite(v)) return "values must be finite";
  }
  return "";
}

}  // namespace manylight
