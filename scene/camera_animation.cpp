#include "scene/camera_animation.h"

#include "scene/gltf_convert.h"

namespace manylight {

glm::mat4 animatedCameraWorld(const Camera& camera, float seconds) {
  if (camera.animation.chain.empty()) return camera.world;
  return gltf::withoutScale(animatedChain(camera.animation.chain, seconds));
}

std::string checkTrack(const AnimationTrack& t) {
  return checkKeys(t.interpolation, t.times, t.values, t.path == AnimationTrack::Rotation ? 4 : 3);
}

}  // namespace manylight
