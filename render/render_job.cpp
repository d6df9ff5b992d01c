#include "render/render_job.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <map>

#include "base/parallel.h"
#include "render/method_choice.h"

namespace manylight {

Camera resolveCamera(const Scene& scene, const RenderRequest& request, bool* framed) {
  if (request.camera >= int(scene.cameras.size())) {
    throw Error(scene.name + ": camera " + std::to_string(request.camera) +
                " does not exist (the scene has " + std::to_string(scene.cameras.size()) + ")");
  }
  if (framed) *framed = scene.cameras.empty();
  if (scene.cameras.empty()) return frameBounds(scene.bounds(), request.width, request.height);
  return scene.cameras[std::max(request.camera, 0)];
}

std::unique_ptr<Renderer> prepareRenderer(const Scene& scene, const std::vector<Light>& lights,
                                          int width, int height, Method method,
                                          const BakeOptions& options, BakedLights baked,
                                          double* bakeMs) {
  LinklessOctree octree;
  std::future<PackedTrees> trees;
  const auto start = std::chrono::steady_clock::now();
  const auto msSince = [&start] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  if (method == Method::Octree && !baked.octree) {
    octree = packLinklessOctree(buildLightOctree(lights, scene, options.octree));
    baked.octree = &octree;
  } else if (method != Method::Reference && method != Method::Octree && !baked.trees) {
    // Built on other threads while the renderer uploads the scene (the trees' build leaves
    // cores idle at times; the upload is the GL thread's).
    trees = std::async(kThreadOrDeferred,
                       [&lights, &options] { return bakeLightTrees(lights, options.trees); });
    baked.pendingTrees = &trees;
  }
  const double buildMs = msSince();
  auto renderer = std::make_unique<Renderer>(scene, lights, width, height, method, baked);
  if (bakeMs) {
    // Trees built here: from the start of their build until the renderer holds them.
    *bakeMs = method == Method::Reference ? 0.0
              : baked.pendingTrees        ? msSince()
                                          : buildMs + renderer->uploadMs();
  }
  return renderer;
}

PreparedRender::PreparedRender(const Scene& scene, const RenderRequest& request)
    : defaultRig(scene.lights.empty()), camera(resolveCamera(scene, request, &framed)) {
  if (defaultRig) rig = defaultLightRig(camera);
  const std::vector<Light>& lights = defaultRig ? rig : scene.lights;
  lightCount = lights.size();
  // An AOV runs no lighting pass, so the reference method, which builds nothing, serves it.
  method = request.aov == Aov::None ? request.method : Method::Reference;
  BakedLights baked;
  if (!defaultRig) baked = {request.prebuiltTrees, request.prebuiltOctree};
  MethodChoice choice;
  if (method == Method::Auto) {
    const auto start = std::chrono::steady_clock::now();
    choice =
        chooseMethod(scene, lights, request.width, request.height, request.octree, baked.octree);
    method = choice.method;
    methodReason = choice.reason;
    if (choice.octree) baked.octree = choice.octree.get();
    bakeMs +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  double prepareMs = 0.0;
  renderer = prepareRenderer(scene, lights, request.width, request.height, method,
                             {request.lightcuts.trees, request.octree}, baked, &prepareMs);
  bakeMs += prepareMs;
  settings.octreeStats = request.octreeStats;
  settings.aov = request.aov;
  settings.ambient = defaultRig && request.rigAmbient ? glm::vec3(kRigAmbient) : request.ambient;
  settings.lightsPerPass = request.lightsPerPass;
  settings.lightcuts = request.lightcuts;
  settings.indirect = request.aov == Aov::None ? request.indirect : IndirectSettings{};
  if (settings.indirect.mode != Indirect::None) renderer->enableIndirect(lights);
}

RenderOutcome renderScene(const Scene& scene, const RenderRequest& request) {
  const PreparedRender p(scene, request);
  RenderOutcome out;
  out.framed = p.framed;
  out.defaultRig = p.defaultRig;
  out.lightCount = p.lightCount;
  out.bakeMs = p.bakeMs;
  out.method = p.method;
  out.methodReason = p.methodReason;
  if (p.renderer->lightcuts()) out.nodeColour = p.renderer->lightcuts()->nodeColour();
  if (p.renderer->octree()) out.octree = summarise(p.renderer->octree()->octree());
  out.image =
      p.renderer->render(makeView(p.camera, request.width, request.height), p.settings, &out.frame);
  return out;
}

double referenceSecondsEstimate(std::size_t lights, int width, int height) {
  return double(lights) * width * height / kReferenceEvaluationsPerSecond;
}

std::vector<Thumbnail> planThumbnails(const std::vector<std::string>& scenes,
                                      const std::string& outDir, const std::string& format,
                                      Shard shard) {
  std::vector<Thumbnail> jobs;
  std::map<std::string, std::string> writer;  // output → the scene that writes it
  for (std::size_t i = std::size_t(shard.index); i < scenes.size(); i += std::size_t(shard.count)) {
    const std::string output = (std::filesystem::path(outDir) /
                                (std::filesystem::path(scenes[i]).stem().string() + "." + format))
                                   .string();
    const auto [it, added] = writer.emplace(output, scenes[i]);
    if (!added) {
      throw Error(scenes[i] + ": would write " + output + ", as " + it->second +
                  " does; give scenes distinct names");
    }
    jobs.push_back({scenes[i], output});
  }
  return jobs;
}

}  // namespace manylight
