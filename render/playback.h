#pragma once
// Kiosk playback (`manylight play`): one renderer for the whole run — the scene, its lights
// and light trees uploaded once — and the camera changing from frame to frame: the chosen
// camera's glTF animation when it has one (frame i at i/fps seconds), otherwise a turntable
// orbit of the camera (or of the thumbnail framing) about the vertical axis through the
// centre of the scene's bounds. Lights that glTF animates (scene/light_animation.h) play
// their animation with it: frame i shows them at i/fps seconds, moved in the renderer
// (Renderer::moveLights).
#include <atomic>
#include <functional>

#include "render/render_job.h"

namespace manylight {

struct PlaybackRequest {
  RenderRequest frame;  // size, camera, method, lights, prebuilt trees
  int frames = 0;       // 0: the animation's length at `fps` (to its last key), or 120 for an orbit
  float fps = 30.0f;
  float orbitDegrees = 360.0f;  // swept over all frames (frame i at i/frames of it)
  // Lightcuts: shared cuts per cell of the scene, kept from frame to frame
  // (LightcutsSettings::keepCuts); false: per square of the screen, every frame anew.
  bool keepCuts = true;
  // Lightcuts: read every frame's cut statistics back into its FrameStats, not only the first
  // frame's (each is a readback of a whole float target).
  bool cutStatsEveryFrame = false;
};

struct PlaybackOutcome {
  int framesRendered = 0;
  bool framed = false;          // no camera: the orbit starts from the thumbnail framing
  bool animated = false;        // the camera's animation was played (no orbit)
  bool lightsAnimated = false;  // the scene's light animation was played
  bool defaultRig = false;      // no lights: the default rig, fixed to the first frame's camera
  std::size_t lightCount = 0;
  double bakeMs = 0.0;
  Method method = Method::Reference;    // the method used (auto's choice for Method::Auto)
  std::string methodReason;             // with Method::Auto: why
  std::vector<double> renderMs;         // per frame
  std::vector<double> cutMs;            // per frame: of renderMs, lightcuts' shared cuts on the CPU
  std::vector<int> cutsMade, cutsKept;  // per frame: shared cuts found, and kept
  std::vector<double> moveMs;           // per frame: moving the lights (light animation only)
  CutStats firstFrameCuts;
};

// Called with each frame in order; returning false stops the playback (a closed output).
using FrameSink = std::function<bool(int frame, const Image& image, const FrameStats& stats)>;

// Plays `scene`; stops early when `stop` becomes true (checked between frames). Needs a
// current context. Throws Error or gl::GlError.
PlaybackOutcome play(const Scene& scene, const PlaybackRequest& request, const FrameSink& sink,
                     const std::atomic<bool>* stop = nullptr);

}  // namespace manylight
