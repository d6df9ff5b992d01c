#include "render/playback.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "scene/camera_animation.h"
#include "scene/light_animation.h"

namespace manylight {

PlaybackOutcome play(const Scene& scene, const PlaybackRequest& request, const FrameSink& sink,
                     const std::atomic<bool>* stop) {
  PlaybackOutcome out;
  const RenderRequest& r = request.frame;
  PreparedRender p(scene, r);
  p.settings.lightcuts.keepCuts = request.keepCuts;
  const Camera& start = p.camera;
  out.framed = p.framed;
  out.defaultRig = p.defaultRig;
  out.lightCount = p.lightCount;
  out.bakeMs = p.bakeMs;
  out.method = p.method;
  out.methodReason = p.methodReason;
  const Bounds bounds = scene.bounds();
  const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);
  const float sweep = glm::radians(request.orbitDegrees);
  out.animated = !start.animation.chain.empty();
  // The scene's own lights play their animation (the default rig stays with the camera).
  const bool lightsMove = !p.defaultRig && scene.lightAnimation.animated();
  out.lightsAnimated = lightsMove;
  const float duration = std::max(out.animated ? start.animation.duration : 0.0f,
                                  lightsMove ? scene.lightAnimation.duration() : 0.0f);
  const int frames = request.frames > 0 ? request.frames
                     : out.animated || lightsMove
                         ? int(std::floor(duration * request.fps + 1e-3f)) + 1
                         : 120;
  std::vector<Light> lights;
  std::vector<int> changed;
  const BakeOptions bake{r.lightcuts.trees, r.octree};
  for (int i = 0; i < frames; ++i) {
    if (stop && stop->load()) break;
    Camera camera = start;
    if (out.animated) {
      camera.world = animatedCameraWorld(start, float(i) / request.fps);
    } else {
      camera = orbitCamera(start, centre, sweep * float(i) / float(frames));
    }
    if (lightsMove) {
      const auto moveStart = std::chrono::steady_clock::now();
      scene.lightAnimation.sampleLights(scene, float(i) / request.fps, lights, &changed);
      if (!changed.empty()) p.renderer->moveLights(lights, changed, bake);
      out.moveMs.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - moveStart)
              .count());
    }
    FrameStats stats;
    // A readback of the whole statistics target: the first frame only, unless asked for.
    p.settings.readCutStats = i == 0 || request.cutStatsEveryFrame;
    const Image image = p.renderer->render(makeView(camera, r.width, r.height), p.settings, &stats);
    out.renderMs.push_back(stats.renderMs);
    out.cutMs.push_back(stats.cutMs);
    out.cutsMade.push_back(stats.cutsMade);
    out.cutsKept.push_back(stats.cutsKept);
    if (i == 0) out.firstFrameCuts = stats.cuts;
    ++out.framesRendered;
    if (!sink(i, image, stats)) break;
  }
  return out;
}

}  // namespace manylight
