#pragma once
// The deferred renderer: a G-buffer pass, then the chosen method's lighting passes into a
// float radiance target, read back as a linear image; or, for an AOV, the G-buffer pass's
// material channel alone.
#include <memory>
#include <string>
#include <vector>

#include "image/image.h"
#include "render/aov.h"
#include "render/blend_pass.h"
#include "render/gbuffer.h"
#include "render/geometry_pass.h"
#include "render/gpu_scene.h"
#include "render/lightcuts_method.h"
#include "render/reference_method.h"
#include "scene/camera.h"

namespace manylight {

enum class Method { Reference, Lightcuts, LightcutsDistance };

// "reference", "lightcuts", "lightcuts-distance" → Method; throws Error naming the choices
// for anything else.
Method parseMethod(const std::string& name);
const char* methodName(Method m);

struct FrameSettings {
  glm::vec3 ambient{0.0f};
  int lightsPerPass = 0;        // 0: ReferenceMethod::lightsPerPass(pixels)
  LightcutsSettings lightcuts;  // the lightcuts methods
  bool readCutStats = true;     // lightcuts: read the per-pixel cut statistics back into FrameStats
  // Reference method: light only the bands of kRowBand rows whose index is a multiple of
  // this (1: every row). For a reference too slow to light whole (bench/); the other rows
  // keep only ambient and emissive light. See rowsLit.
  int rowBandStride = 1;
  // Not None: the image is this material channel (render/aov.h), with no lighting pass.
  Aov aov = Aov::None;
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
  // method uploads `trees`, baked for these lights (bakeLightTrees or a baked file), and
  // needs them: Error when they are missing. Throws gl::GlError.
  Renderer(const Scene& scene, const std::vector<Light>& lights, int width, int height,
           Method method, const PackedTrees* trees = nullptr);
  // Milliseconds spent uploading the light trees (lightcuts methods; else 0).
  double uploadMs() const { return uploadMs_; }
  // The lightcuts method, or null for the reference method.
  const LightcutsMethod* lightcuts() const { return lightcuts_.get(); }

  // Reference method only: lights the next frames with `lights` instead (probes that change
  // one light's colour, without uploading the geometry again). Throws gl::GlError.
  void replaceLights(const std::vector<Light>& lights);

  // Renders one frame seen through `view`. Throws gl::GlError on a driver error.
  Image render(const View& view, const FrameSettings& settings, FrameStats* stats = nullptr);

 private:
  int lightReference(const View& view, const FrameSettings& settings);
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
  double uploadMs_ = 0.0;
  gl::VertexArray emptyVao_;  // the full-screen triangle needs a bound VAO in core profile
};

}  // namespace manylight
