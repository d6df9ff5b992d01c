#pragma once
// The reference method: every light at every pixel, exact up to float arithmetic. Ground
// truth for every other method.
#include "gl/objects.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"

namespace manylight {

class ReferenceMethod {
 public:
  // Compiles the lighting program; needs a current context. Throws gl::GlError.
  ReferenceMethod();

  // Adds every light's contribution to the radiance target of `gbuffer`, in passes of at
  // most lightsPerPass(...) lights. Returns the number of passes.
  int light(const GpuScene& scene, const GBuffer& gbuffer, const View& view) const;

  // Lights per additive pass: about kEvaluationsPerPass light evaluations per draw, so no
  // single draw runs long enough to trip a GPU watchdog, while the per-pass cost (reading
  // the G-buffer again) stays under 1% of the work.
  static int lightsPerPass(int pixels);
  static constexpr long long kEvaluationsPerPass = 1ll << 26;

 private:
  gl::Program program_;
};

}  // namespace manylight
