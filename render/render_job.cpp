#include "render/render_job.h"

#include <filesystem>
#include <map>

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
  Renderer renderer(scene, lights, request.width, request.height, request.method, request.lightcuts.trees,
                    out.defaultRig ? nullptr : request.prebuiltTrees);
  FrameSettings settings;
  settings.ambient = request.ambient;
  settings.lightsPerPass = request.lightsPerPass;
  settings.lightcuts = request.lightcuts;
  out.bakeMs = renderer.bakeMs();
  if (renderer.lightcuts()) out.nodeColour = renderer.lightcuts()->nodeColour();
  out.image = renderer.render(makeView(camera, request.width, request.height), settings, &out.frame);
  return out;
}

std::vector<Thumbnail> planThumbnails(const std::vector<std::string>& scenes, const std::string& outDir,
                                      const std::string& format, Shard shard) {
  std::vector<Thumbnail> jobs;
  std::map<std::string, std::string> writer;  // output → the scene that writes it
  for (std::size_t i = std::size_t(shard.index); i < scenes.size(); i += std::size_t(shard.count)) {
    const std::string output =
        (std::filesystem::path(outDir) / (std::filesystem::path(scenes[i]).stem().string() + "." + format)).string();
    const auto [it, added] = writer.emplace(output, scenes[i]);
    if (!added) {
      throw Error(scenes[i] + ": would write " + output + ", as " + it->second + " does; give scenes distinct names");
    }
    jobs.push_back({scenes[i], output});
  }
  return jobs;
}

}  // namespace manylight
