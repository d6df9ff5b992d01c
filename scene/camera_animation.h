#pragma once
// Camera animations as glTF 2.0 defines them (§3.11): translation, rotation and scale
// channels of the camera's node and its ancestors, with LINEAR (rotation: spherical),
// STEP or CUBICSPLINE interpolation, clamped outside the keys.
#include <string>

#include "scene/scene.h"

namespace manylight {

// The camera-to-world transform of `camera` at `seconds` (clamped to the keys), scale
// removed as for a still camera. A camera without animation gives its `world`.
glm::mat4 animatedCameraWorld(const Camera& camera, float seconds);

// What is wrong with a track (times not finite and increasing, values not matching the
// keys), or "" when it is sound.
std::string checkTrack(const AnimationTrack& track);

}  // namespace manylight
