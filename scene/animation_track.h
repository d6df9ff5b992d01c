#pragma once
// glTF 2.0 animation tracks (§3.11) and their evaluation, shared by the camera animations
// (scene/camera_animation.h) and the light animations (scene/light_animation.h): LINEAR
// (rotations spherical), STEP and CUBICSPLINE keys, clamped outside the keys.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace manylight {

// A node's translation, rotation or scale over time.
struct AnimationTrack {
  enum Path : std::uint8_t { Translation, Rotation, Scale } path = Translation;
  enum Interpolation : std::uint8_t { Linear, Step, CubicSpline } interpolation = Linear;
  std::vector<float> times;   // seconds, increasing
  std::vector<float> values;  // 3 (4 for rotation, xyzw) floats per key; ×3 for cubic spline
};
// A node of an animated chain: its rest transform and the tracks that move it.
struct AnimatedNode {
  glm::mat4 matrix{1.0f};  // used when the node gives a matrix (such nodes are not animated)
  bool hasMatrix = false;
  glm::vec3 translation{0.0f};
  glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // quaternion xyzw
  glm::vec3 scale{1.0f};
  std::vector<AnimationTrack> tracks;
};

// The value at `seconds` of keys `times` with `components` floats each in `values` (×3 for
// cubic splines: in-tangent, value, out-tangent). `spherical`: LINEAR keys are quaternions
// (xyzw), slerped. Unused components are 0. The keys must pass checkKeys.
glm::vec4 sampleKeys(AnimationTrack::Interpolation interpolation, const std::vector<float>& times,
                     const std::vector<float>& values, int components, bool spherical,
                     float seconds);

// What is wrong with such keys (times not finite, not >= 0 or not increasing, values not
// finite or not matching the keys), or "" when they are sound.
std::string checkKeys(AnimationTrack::Interpolation interpolation, const std::vector<float>& times,
                      const std::vector<float>& values, int components);

// The node's local transform at `seconds`: its matrix when it has one or no tracks (that is
// the loader's rest transform), else translation · rotation · scale composed in double as
// the loader composes a node's, the tracks' values replacing the rest ones (the last track
// of a path wins).
glm::mat4 animatedLocal(const AnimatedNode& node, float seconds);

// The product of the chain's local transforms at `seconds`, root first, in float as the
// loader multiplies a node's world transform.
glm::mat4 animatedChain(const std::vector<AnimatedNode>& chain, float seconds);

}  // namespace manylight
