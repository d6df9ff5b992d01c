#pragma once
// The deferred renderer: a G-buffer pass, then the chosen method's lighting passes into a
// float radiance target, read back as a linear image; or, for an AOV, the G-buffer pass's
// material channel alone.
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "bake/octree_update.h"
#include "bake/tree_update.h"
#include "image/image.h"
#include "render/aov.h"
#include "render/blend_pass.h"
#include "render/gbuffer.h"
#include "render/geometry_pass.h"
#include "render/gpu_scene.h"
#include "render/indirect_light.h"
#include "render/lightcuts_method.h"
#include "render/octree_method.h"
#include "render/reference_method.h"
#include "scene/camera.h"

namespace manylight {

// Auto is a request only (render/method_choice.h resolves it); a Renderer takes the others.
enum class Method { Reference, Lightcuts, LightcutsDistance, Octree, Auto };

// "reference", "lightcuts", "lightcuts-distance", "octree", "auto" → Method; throws Error
// naming the choices for anything else.
Method parseMethod(const std::string& name);
const char* methodName(Method m);

struct FrameSettings {
  glm::vec3 ambient{0.0f};
  int lightsPerPass = 0;        // 0: ReferenceMethod::lightsPerPass(pixels); octree: list entries
  LightcutsSettings lightcuts;  // the lightcuts methods
  bool readCutStats = true;     // lightcuts: read the per-pixel cut statistics back into FrameStats
  // Reference method: light only the bands of kRowBand rows whose index is a multiple of
  // this (1: every row). For a reference too slow to light whole (bench/); the other rows
  // keep only ambient and emissive light. See rowsLit.
  int rowBandStride = 1;
  // Not None: the image is this material channel (render/aov.h), with no lighting pass.
  Aov aov = Aov::None;
  // The octree method: count each pixel's list entries and the lights reaching it into
  // FrameStats (on the CPU, from the G-buffer read back).
  bool octreeStats = false;
  // One bounce of indirect light (Renderer::enableIndirect must have given the lights).
  IndirectSettings indirect;
};

inline constexpr int kRowBand = 8;
// Per row of a `height`-row image (top-down): whether a frame with `rowBandStride` lights it.
std::vector<bool> rowsLit(int height, int rowBandStride);

struct FrameStats {
  double renderMs = 0.0;  // G-buffer + lighting passes, bracketed by glFinish
  double cutMs = 0.0;     // of which lightcuts' shared cuts on the CPU (LightcutsMethod::cutMs)
  int cutsMade = 0, cutsKept = 0;  // shared cuts found, and kept from earlier frames
  int lightingPasses = 0;          // 0 for an AOV
  CutStats cuts;                   // lightcuts methods only
  OctreeFrameStats octree;         // the octree method with FrameSettings::octreeStats
  IndirectStats indirect;          // FrameSettings::indirect
};

// What the methods take baked for the lights (a baked file's, or built by prepareRenderer):
// the light trees of the lightcuts methods, the linkless octree of the octree method.
struct BakedLights {
  PackedTrees* trees = nullptr;  // taken by the renderer: left empty
  const LinklessOctree* octree = nullptr;
  // Trees still being built (by prepareRenderer, on other threads) when `trees` is null: the
  // renderer uploads the scene and sizes its targets first, then waits for them.
  std::future<PackedTrees>* pendingTrees = nullptr;
};

// How what a method needs is baked when it is not given baked.
struct BakeOptions {
  TreeOptions trees;
  OctreeOptions octree;
};

// Renders one triangle with the default material at 8×8 and throws the image away:
// llvmpipe builds a program's machine code at its first draw in each draw state and keeps it
// for the context's later draws in that state.
// Called while another thread reads the scene, this takes that work off a render's
// critical path for every untextured draw. (A textured draw's code depends on its
// texture's size and sampler, which are not known before the scene is read.) Needs a
// current context. Throws gl::GlError.
void warmUpGeometryPass(Aov aov = Aov::None);

class Renderer {
 public:
  // Uploads the scene and compiles the programs; needs a current context. A lightcuts
  // method uploads `baked.trees`, the octree method `baked.octree`, baked for these lights
  // (bake/ or a baked file), and needs them: Error when they are missing. Throws gl::GlError.
  Renderer(const Scene& scene, const std::vector<Light>& lights, int width, int height,
           Method method, BakedLights baked = {});
  // Milliseconds spent uploading the light trees or the octree (else 0).
  double uploadMs() const { return uploadMs_; }
  // The lightcuts method, or null for the others.
  const LightcutsMethod* lightcuts() const { return lightcuts_.get(); }
  // The octree method, or null for the others.
  const OctreeMethod* octree() const { return octree_.get(); }
  // The G-buffer of the last frame.
  const GBuffer& gbuffer() const { return gbuffer_; }

  // Reference method only: lights the next frames with `lights` instead (probes that change
  // one light's colour, without uploading the geometry again). Throws gl::GlError.
  void replaceLights(const std::vector<Light>& lights);

  // Lights the next frames with `lights`, the construction's lights of which those listed in
  // `changed` (scene indices) moved or changed (an animation). The octree method updates its
  // octree in place (bake/octree_update.h); the lightcuts methods refit their trees in place
  // (bake/tree_update.h), upload them again and drop every kept cut. Both build theirs with
  // `options` at the first call.
  // Throws gl::GlError.
  void moveLights(const std::vector<Light>& lights, const std::vector<int>& changed,
                  const BakeOptions& options);

  // Lets frames add indirect light (FrameSettings::indirect) from `lights`, the
  // construction's, which it keeps a copy of (moveLights updates it).
  void enableIndirect(const std::vector<Light>& lights) { indirectLights_ = lights; }

  // Renders one frame seen through `view`. Throws gl::GlError on a driver error.
  Image render(const View& view, const FrameSettings& settings, FrameStats* stats = nullptr);

 private:
  int lightReference(const View& view, const FrameSettings& settings);
  // Starts the frame's indirect light (IndirectLight::begin) once its G-buffer is drawn.
  void beginIndirect(const View& view, const IndirectSettings& settings);
  // Adds the frame's indirect light (FrameSettings::indirect) to the radiance target.
  void lightIndirect(const View& view, const IndirectSettings& settings, FrameStats* stats);
  // The G-buffer pass of `aov`'s variant, made at its first use.
  const GeometryPass& aovPass(Aov aov);

  const Scene& scene_;
  GpuScene gpu_;
  GBuffer gbuffer_;
  GeometryPass geometry_;
  std::unique_ptr<BlendPass> blend_;  // made on the first frame with blended draws
  std::unique_ptr<GeometryPass> aovGeometry_;
  ReferenceMethod reference_;
  std::unique_ptr<LightcutsMethod> lightcuts_;
  std::unique_ptr<OctreeMethod> octree_;
  std::unique_ptr<DynamicOctree> dynamic_;   // the octree method's, once lights move
  std::unique_ptr<DynamicTrees> trees_;      // the lightcuts methods', once lights move
  std::vector<Light> indirectLights_;        // enableIndirect's
  std::unique_ptr<IndirectLight> indirect_;  // made on the first frame that asks for it
  bool distance_ = false;                    // lightcuts-distance
  double uploadMs_ = 0.0;
  gl::VertexArray emptyVao_;  // the full-screen triangle needs a bound VAO in core profile
};

}  // namespace manylight
