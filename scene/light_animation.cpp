#include "scene/light_animation.h"

#include <algorithm>
#include <cmath>

#include "scene/gltf_convert.h"
#include "scene/scene.h"

namespace manylight {
namespace {

constexpr float kHalfPi = 1.57079632679489661923f;

int components(const LightPropertyTrack& t) {
  return t.property == LightPropertyTrack::Colour ? 3 : 1;
}

void apply(const LightPropertyTrack& t, float seconds, Light& l) {
  const glm::vec4 v = sampleKeys(t.interpolation, t.times, t.values, components(t), false, seconds);
  switch (t.property) {
    case LightPropertyTrack::Colour:
      l.colour = glm::max(glm::vec3(v), glm::vec3(0.0f));
      break;
    case LightPropertyTrack::Intensity:
      l.intensity = std::max(v.x, 0.0f);
      break;
    case LightPropertyTrack::Range:
      l.range = std::max(v.x, 0.0f);
      break;
    case LightPropertyTrack::InnerConeAngle:
      l.innerConeAngle = std::clamp(v.x, 0.0f, kHalfPi);
      break;
    case LightPropertyTrack::OuterConeAngle:
      l.outerConeAngle = std::clamp(v.x, 0.0f, kHalfPi);
      break;
  }
}

// Keeps 0 <= inner < outer <= π/2, as the loader requires of a spot light.
void settleCone(Light& l) {
  if (l.type != LightType::Spot || l.innerConeAngle < l.outerConeAngle) return;
  if (l.outerConeAngle <= 0.0f) l.outerConeAngle = std::nextafter(0.0f, 1.0f);
  l.innerConeAngle = std::nextafter(l.outerConeAngle, 0.0f);
}

Light sampleLight(const AnimatedLight& a, const Light& rest, float seconds) {
  Light l = rest;
  if (!a.chain.empty()) gltf::placeLight(l, animatedChain(a.chain, seconds));
  for (const LightPropertyTrack& t : a.properties) apply(t, seconds, l);
  if (!a.properties.empty()) settleCone(l);
  return l;
}

}  // namespace

bool LightAnimation::animated() const { return !lights.empty(); }

float LightAnimation::duration() const {
  float last = 0.0f;
  for (const AnimatedLight& a : lights) {
    for (const AnimatedNode& n : a.chain) {
      for (const AnimationTrack& t : n.tracks) last = std::max(last, t.times.back());
    }
    for (const LightPropertyTrack& t : a.properties) last = std::max(last, t.times.back());
  }
  return last;
}

void LightAnimation::sampleLights(const Scene& scene, float seconds, std::vector<Light>& out,
                                  std::vector<int>* changed) const {
  if (out.size() != scene.lights.size()) out = scene.lights;
  if (changed) changed->clear();
  for (const AnimatedLight& a : lights) {
    const std::size_t i = std::size_t(a.light);
    const Light l = sampleLight(a, scene.lights[i], seconds);
    if (sameLight(l, out[i])) continue;
    out[i] = l;
    if (changed) changed->push_back(a.light);
  }
}

std::string checkLightTrack(const LightPropertyTrack& t) {
  const std::string problem = checkKeys(t.interpolation, t.times, t.values, components(t));
  if (!problem.empty()) return problem;
  const bool cone = t.property == LightPropertyTrack::InnerConeAngle ||
                    t.property == LightPropertyTrack::OuterConeAngle;
  const std::size_t stride = t.interpolation == AnimationTrack::CubicSpline ? 3 : 1;
  const std::size_t n = std::size_t(components(t));
  for (std::size_t k = 0; k < t.times.size(); ++k) {
    for (std::size_t c = 0; c < n; ++c) {
      const float v = t.values[(k * stride + (stride == 3 ? 1 : 0)) * n + c];
      if (v < 0.0f) return "values must not be negative";
      if (cone && v > kHalfPi) return "cone angles must not exceed pi/2";
    }
  }
  return "";
}

}  // namespace manylight
