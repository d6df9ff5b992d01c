#include "scene/animation_track.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace manylight {
namespace {

struct Keys {
  const std::vector<float>& times;
  const std::vector<float>& values;
  int components;
  std::size_t stride;  // 3 for cubic splines, else 1

  glm::vec4 key(std::size_t k, int part) const {  // part: 0 in-tangent, 1 value, 2 out-tangent
    const std::size_t at =
        (k * stride + (stride == 3 ? std::size_t(part) : 0)) * std::size_t(components);
    glm::vec4 v(0.0f);
    for (int c = 0; c < components; ++c) v[c] = values[at + std::size_t(c)];
    return v;
  }
};

glm::vec4 hermite(const Keys& keys, std::size_t k0, float dt, float u) {
  const float u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * keys.key(k0, 1) + dt * (u3 - 2 * u2 + u) * keys.key(k0, 2) +
         (-2 * u3 + 3 * u2) * keys.key(k0 + 1, 1) + dt * (u3 - u2) * keys.key(k0 + 1, 0);
}

glm::vec4 slerp(const glm::vec4& a, const glm::vec4& b, float u) {
  const glm::quat q = glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), u);
  return {q.x, q.y, q.z, q.w};
}

}  // namespace

glm::vec4 sampleKeys(AnimationTrack::Interpolation interpolation, const std::vector<float>& times,
                     const std::vector<float>& values, int components, bool spherical,
                     float seconds) {
  const Keys keys{times, values, components,
                  interpolation == AnimationTrack::CubicSpline ? std::size_t(3) : 1};
  const std::size_t count = times.size();
  if (seconds <= times.front() || count == 1) return keys.key(0, 1);
  if (seconds >= times.back()) return keys.key(count - 1, 1);
  const std::size_t k1 =
      std::size_t(std::upper_bound(times.begin(), times.end(), seconds) - times.begin());
  const std::size_t k0 = k1 - 1;
  const float dt = times[k1] - times[k0];
  const float u = (seconds - times[k0]) / dt;
  switch (interpolation) {
    case AnimationTrack::Step:
      return keys.key(k0, 1);
    case AnimationTrack::CubicSpline:
      return hermite(keys, k0, dt, u);
    default:
      if (spherical) return slerp(keys.key(k0, 1), keys.key(k1, 1), u);
      return glm::mix(keys.key(k0, 1), keys.key(k1, 1), u);
  }
}

std::string checkKeys(AnimationTrack::Interpolation interpolation, const std::vector<float>& times,
                      const std::vector<float>& values, int components) {
  if (times.empty()) return "no keys";
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]) || times[k] < 0.0f) return "key times must be finite and >= 0";
    if (k > 0 && !(times[k] > times[k - 1])) return "key times must increase";
  }
  const std::size_t per =
      std::size_t(components) * (interpolation == AnimationTrack::CubicSpline ? 3 : 1);
  if (values.size() != times.size() * per) {
    return std::to_string(values.size()) + " values for " + std::to_string(times.size()) +
           " keys, expected " + std::to_string(times.size() * per);
  }
  for (float v : values) {
    if (!std::isfinite(v)) return "values must be finite";
  }
  return "";
}

glm::mat4 animatedLocal(const AnimatedNode& n, float seconds) {
  if (n.hasMatrix || n.tracks.empty()) return n.matrix;
  glm::vec3 translation = n.translation, scale = n.scale;
  glm::vec4 rotation = n.rotation;
  for (const AnimationTrack& t : n.tracks) {
    const bool isRotation = t.path == AnimationTrack::Rotation;
    const glm::vec4 v =
        sampleKeys(t.interpolation, t.times, t.values, isRotation ? 4 : 3, isRotation, seconds);
    if (t.path == AnimationTrack::Translation) translation = glm::vec3(v);
    if (isRotation) rotation = v;
    if (t.path == AnimationTrack::Scale) scale = glm::vec3(v);
  }
  // As the loader's localTransform: translate · rotate (normalised; a zero quaternion gives
  // the identity) · scale, in double.
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(translation));
  m *= glm::mat4_cast(glm::normalize(glm::dquat(rotation.w, rotation.x, rotation.y, rotation.z)));
  m = glm::scale(m, glm::dvec3(scale));
  return glm::mat4(m);
}

glm::mat4 animatedChain(const std::vector<AnimatedNode>& chain, float seconds) {
  glm::mat4 world(1.0f);
  for (const AnimatedNode& n : chain) world = world * animatedLocal(n, seconds);
  return world;
}

}  // namespace manylight
