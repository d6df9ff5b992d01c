#pragma once
// One still image of a scene: picks the camera (the scene's, or the thumbnail framing) and
// the lights (the scene's, or the default rig), then renders. Shared by the CLI and tests.
#include <memory>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace manylight {

struct RenderRequest {
  int width = 640;
  int height = 480;
  int camera = -1;  // index into Scene::cameras; −1: the first camera, or framing if none
  Method method = Method::Reference;
  glm::vec3 ambient{0.0f};
  // Where the scene has no lights, the default rig's ambient (kRigAmbient) instead of
  // `ambient`: what a command line without --ambient asks for.
  bool rigAmbient = false;
  int lightsPerPass = 0;  // 0: automatic
  LightcutsSettings lightcuts;
  OctreeOptions octree;  // the octree method: how its octree is built (when it is built)
  // Lightcuts trees packed before for the scene's own lights (a baked scene); null: build.
  // The render takes them (they are left empty): at 2^20 lights they are 136 MB.
  PackedTrees* prebuiltTrees = nullptr;
  // The same for the octree method's octree.
  const LinklessOctree* prebuiltOctree = nullptr;
  bool octreeStats = false;   // FrameSettings::octreeStats
  IndirectSettings indirect;  // FrameSettings::indirect (none for an AOV)
  // Not None: the image is this material channel (render/aov.h), lit by nothing; no light
  // trees are built for it.
  Aov aov = Aov::None;
};

struct RenderOutcome {
  Image image;
  FrameStats frame;
  bool framed = false;      // no camera: the thumbnail framing of scene/camera.h was used
  bool defaultRig = false;  // no lights: the default rig of scene/camera.h was used
  std::size_t lightCount = 0;
  double bakeMs = 0.0;         // light trees built and uploaded (lightcuts methods)
  NodeColourCoder nodeColour;  // lightcuts methods: how node colours were coded, and the error
  OctreeSummary octree;        // the octree method: its octree's figures
  Method method = Method::Reference;  // the method used (auto's choice for Method::Auto)
  std::string methodReason;           // with Method::Auto: why
};

// The camera a request resolves to. Throws Error ("SCENE: camera N does not exist ...") for a
// camera index the scene lacks.
Camera resolveCamera(const Scene& scene, const RenderRequest& request, bool* framed = nullptr);

// What a request sets up before its first frame (a still or a playback): the camera, the
// lights (the scene's, or the default rig fixed to that camera), a renderer for them, and
// the frame settings. Needs a current context. Throws Error or gl::GlError.
// A renderer for `lights`: a lightcuts method uploads `baked.trees`, the octree method
// `baked.octree` (a baked file's), or, where it is null, what is baked here with `options`.
// Trees baked here are built on other threads while the renderer uploads the scene. `bakeMs`:
// the milliseconds from the start of baking them to their upload (0 for the reference).
std::unique_ptr<Renderer> prepareRenderer(const Scene& scene, const std::vector<Light>& lights,
                                          int width, int height, Method method,
                                          const BakeOptions& options = {}, BakedLights baked = {},
                                          double* bakeMs = nullptr);

struct PreparedRender {
  PreparedRender(const Scene& scene, const RenderRequest& request);
  // Before `camera`: its initialiser sets `framed`.
  bool framed = false;      // no camera: the thumbnail framing
  bool defaultRig = false;  // no lights: the default rig
  Camera camera;
  std::vector<Light> rig;
  std::size_t lightCount = 0;
  // Milliseconds spent baking (when no baked trees were given) and uploading the light trees.
  double bakeMs = 0.0;
  Method method = Method::Reference;  // the method used: request.method, or auto's choice
  std::string methodReason;           // with Method::Auto: why it chose that
  std::unique_ptr<Renderer> renderer;
  FrameSettings settings;
};

// Light evaluations a second of the reference method on llvmpipe with 2 cores: the
// reference throughput of docs/performance.md, rounded.
inline constexpr double kReferenceEvaluationsPerSecond = 4e8;
// Seconds a reference frame of `lights` over width × height takes at
// kReferenceEvaluationsPerSecond when every pixel is covered (background pixels cost nothing).
double referenceSecondsEstimate(std::size_t lights, int width, int height);

// Renders with the current context. Throws Error (bad request) or gl::GlError.
RenderOutcome renderScene(const Scene& scene, const RenderRequest& request);

// A batch of thumbnails (`render --out-dir`): which scenes this machine renders, and where.
struct Shard {
  int index = 0;  // 0 <= index < count
  int count = 1;
};
struct Thumbnail {
  std::string scene, output;
};
// Scenes index, index + count, ... of `scenes` (in the order given), each to
// outDir/STEM.format. Throws Error when two of them would write the same file.
std::vector<Thumbnail> planThumbnails(const std::vector<std::string>& scenes,
                                      const std::string& outDir, const std::string& format,
                                      Shard shard);

}  // namespace manylight
