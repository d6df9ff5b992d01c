#include "render/render_job.h"

namespace manylight {

Camera resolveCamera(const Scene& scene, const RenderRequest& request, bool* framed) {
  if (request.camera >= int(scene.cameras.size())) {
    throw Error(scene.name + ": camera " + std::to_string(request.camera) + " does not exist (the scene has " +
                std::to_string(scene.cameras.size()) + ")");
  }
  if (framed) *framed = scene.cameras.empty();
  if (scene.cameras.empty()) return frameBounds(scene.bounds(), request.width, request.height);
  return scene.cameras[std::max(request.camera, 0)];
}

RenderOutcome renderScene(const Scene& scene, const RenderRequest& request) {
  RenderOutcome out;
  const Camera camera = resolveCamera(scene, request, &out.framed);
  out.defaultRig = scene.lights.empty();
  const std::vector<Light> rig = out.defaultRig ? defaultLightRig(camera) : std::vector<Light>{};
  const std::vector<Light>& lights = out.defaultRig ? rig : scene.lights;
  out.lightCount = lights.size();
  Renderer renderer(scene, lights, request.width, request.height, request.method, request.lightcuts.trees);
  FrameSettings settings;
  settings.ambient = request.ambient;
  settings.lightsPerPass = request.lightsPerPass;
  settings.lightcuts = request.lightcuts;
  out.bakeMs = renderer.bakeMs();
  if (renderer.lightcuts()) out.nodeColour = renderer.lightcuts()->nodeColour();
  out.image = renderer.render(makeView(camera, request.width, request.height), settings, &out.frame);
  return out;
}

}  // namespace manylight
