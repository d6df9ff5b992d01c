#pragma once
// The reference method: every light at every pixel, exact up to float arithmetic. Ground
// truth for every other method.
#include <string>
#include <vector>

#include "gl/objects.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"

namespace manylight {

class ReferenceMethod {
 public:
  // Needs a current context. Programs are compiled on first use, one per variant, and kept
  // by the context (gl::Context::program).
  ReferenceMethod() = default;

  // The #defines of the lighting program for a scene: its light types and whether any
  // material has a specular term. Never its light count.
  static std::vector<std::string> variant(const GpuScene& scene);

  // Adds every light's contribution to the radiance target of `gbuffer`, in passes of at
  // most `perPass` lights (0: lightsPerPass(pixels)). Returns the number of passes.
  int light(const GpuScene& scene, const GBuffer& gbuffer, const View& view, int perPass = 0) const;

  // Lights per additive pass: about kEvaluationsPerPass light evaluations per draw, so no
  // single draw runs long enough to trip a GPU watchdog, while the per-pass cost (reading
  // the G-buffer again) stays under 1% of the work.
  static int lightsPerPass(int pixels);
  static constexpr long long kEvaluationsPerPass = 1ll << 28;
  // And at most this many lights: llvmpipe silently ends all loops of a shader invocation
  // after 65,535 iterations in all (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), and the light
  // loops, unrolled by four, run a quarter as many iterations as lights (plus ≤ 3 per type).
  static constexpr int kMaxLightsPerPass = 1 << 16;

 private:
  // Compiles (once per context) and returns the program for `defines`. Throws gl::GlError.
  const gl::Program& program(const std::vector<std::string>& defines) const;
};

}  // namespace manylight
