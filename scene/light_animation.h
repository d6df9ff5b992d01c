#pragma once
// Lights that glTF animations move and change, evaluated at any time. A light moves with its
// node and the node's ancestors (translation, rotation and scale channels, targeted by node
// or by a KHR_animation_pointer "/nodes/N/..." pointer); its colour, intensity, range and
// spot cone angles change by KHR_animation_pointer channels on
// "/extensions/KHR_lights_punctual/lights/N/...". Every glTF animation that moves or changes
// a light takes part, all playing together from t = 0; where several channels drive one
// property, the last (by animation, then channel) wins. A glTF light used by several nodes is
// one Scene light per node, each with its own chain and the light's property tracks.
//
// As the loader places a light: position = the node's world origin, direction (spot,
// directional) = the node's world −Z, normalised; node scale leaves range and cone angles
// alone (KHR_lights_punctual). At times where every track holds its rest value, sampleLights
// gives Scene::lights bit for bit.
#include <cstdint>
#include <vector>

#include "scene/animation_track.h"

namespace manylight {

struct Light;
struct Scene;

// One animated property of a light: 3 floats a key for colour, 1 for the others; ×3 for
// cubic splines (in-tangent, value, out-tangent).
struct LightPropertyTrack {
  enum Property : std::uint8_t { Colour, Intensity, Range, InnerConeAngle, OuterConeAngle };
  Property property = Intensity;
  AnimationTrack::Interpolation interpolation = AnimationTrack::Linear;
  std::vector<float> times;  // seconds, increasing
  std::vector<float> values;
};

// What animates Scene::lights[light].
struct AnimatedLight {
  int light = 0;
  std::vector<AnimatedNode> chain;  // root first, the light's node last; empty: it does not move
  std::vector<LightPropertyTrack> properties;
};

struct LightAnimation {
  std::vector<AnimatedLight> lights;  // by increasing AnimatedLight::light

  // Whether any light is animated.
  bool animated() const;
  // Seconds: the last key time over all light tracks; 0 when nothing is animated.
  float duration() const;
  // The scene's lights at `seconds` (clamped to the keys) into `out`; lights that are not
  // animated equal Scene::lights. `out` holds the previous call's lights: when its size is
  // not that of Scene::lights it is first set to Scene::lights, and only animated lights are
  // written. `changed` (optional): the indices, increasing, of the lights whose values now
  // differ from what `out` held (the previous call's, or Scene::lights on the first call).
  // Sampled values are kept valid: colour, intensity and range not below 0, cone angles in
  // [0, π/2] with inner below outer; a transform that collapses a light's direction keeps
  // its rest direction.
  void sampleLights(const Scene& scene, float seconds, std::vector<Light>& out,
                    std::vector<int>* changed = nullptr) const;
};

// What is wrong with a property track (as checkTrack says for node tracks), or "".
std::string checkLightTrack(const LightPropertyTrack& track);

}  // namespace manylight
