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

// The light rig used when a scene has no lights: three white directional lights fixed to the
// camera (key 1.5 lux from the upper left, fill 0.5 lux from the right, rim 0.75 lux from
// behind) and, unless the render asks for another, the ambient radiance kRigAmbient. A white
// Lambert surface gets at most (1.5 + 0.5 + 0.75)/π + 0.1 = 0.98 however it faces, so
// nothing clips, and every surface it reaches gets at least the ambient share (metals
// included: scene/shading_model.h), so nothing is black.
std::vector<Light> defaultLightRig(const Camera& camera);
inline constexpr float kRigAmbient = 0.1f;

}  // namespace manylight
