#pragma once
// Camera matrices, the thumbnail framing and the default light rig.
#include <vector>

#include "scene/scene.h"

namespace manylight {

// What a render needs of a camera at a given image size.
struct View {
  glm::mat4 view{1.0f};                  // world → camera
  glm::mat4 projection{1.0f};            // camera → clip (OpenGL conventions)
  glm::vec3 eye{0.0f};                   // world-space position (perspective)
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // world-space viewing direction
  bool orthographic = false;
};

// The glTF camera seen through an image of width × height pixels. The image's aspect ratio
// wins over the camera's aspectRatio, so the picture is never stretched.
View makeView(const Camera& camera, int width, int height);

// The thumbnail camera: looks at the centre of `bounds` from azimuth 45° (from +Z towards
// +X), elevation 30°, vertical field of view 45°, at the distance where the bounding sphere
// fits the narrower field of view with 5% margin.
Camera frameBounds(const Bounds& bounds, int width, int height);

// `camera` turned by `radians` about the vertical (+Y) axis through `centre`: one step of a
// turntable orbit (positive turns counter-clockwise seen from above).
Camera orbitCamera(const Camera& camera, glm::vec3 centre, float radians);

// The light rig used when a scene has no lights: three directional lights fixed to the
// camera (key 3 lux from upper left, fill 1 lux from the right, rim 1.5 lux from behind),
// white, so a Lambert surface facing the key reads as light grey.
std::vector<Light> defaultLightRig(const Camera& camera);

}  // namespace manylight
