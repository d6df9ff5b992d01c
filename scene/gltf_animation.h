#pragma once
// Reads glTF animations (§3.11, and KHR_animation_pointer channels on lights and nodes) into
// the camera and light animations of scene/camera_animation.h and scene/light_animation.h.
// Internal to scene/.
#include <vector>

#include "scene/scene.h"

namespace tinygltf {
class Model;
}  // namespace tinygltf

namespace manylight::gltf {

struct BulkArrays;
struct NodeRecord;

// A node's local transform as the loader places it (matrix, or T · R · S in double).
glm::mat4 localTransform(const BulkArrays& bulk, const NodeRecord& node);

// The first animation that moves node `node` or an ancestor (translation, rotation and scale
// channels that name the node): the chain from the root down to the node, with that
// animation's tracks on each; empty when none. `parent`: each node's parent, −1 for roots.
// Throws SceneError "animation A: channel C: problem" for a broken track.
CameraAnimation cameraAnimation(const tinygltf::Model& model, const BulkArrays& bulk,
                                const std::vector<int>& parent, int node);

// Where Scene::lights[i] comes from: the node that places it and its glTF light.
struct LightSource {
  int node = 0;
  int light = 0;
};

// What animates the lights placed by `sources` (one per Scene light, in order), from every
// animation. Channels whose KHR_animation_pointer targets neither a light nor a node's
// translation, rotation or scale are ignored. Throws SceneError "animation A: channel C:
// problem" for a broken track (or negative values, or cone angles above π/2) and for a track
// on a node with a matrix, and "animation A: channel C: pointer 'P': problem" for a pointer
// into KHR_lights_punctual that names no light, or no animatable property of it.
LightAnimation lightAnimation(const tinygltf::Model& model, const BulkArrays& bulk,
                              const std::vector<LightSource>& sources);

}  // namespace manylight::gltf
