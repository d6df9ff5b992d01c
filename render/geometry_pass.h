#pragma once
// The deferred path's first pass: every opaque and masked primitive into the G-buffer, with
// its material's factors and textures (glsl/gbuffer.frag); one at a time, the blended ones
// (render/blend_pass.h); or, for an AOV, one material channel of theirs into the radiance
// target.
#include <array>
#include <glm/glm.hpp>

#include "gl/objects.h"
#include "render/aov.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace manylight {

class GeometryPass {
 public:
  // Compiles (or takes the context's cached) program, the lit one or that of `aov`; needs a
  // current context.
  explicit GeometryPass(Aov aov = Aov::None);
  Aov aov() const { return aov_; }

  // What draw() draws: every draw but the blended ones, or every draw (the material channel
  // outputs, which show the nearest surface whatever its alpha mode).
  static constexpr int kOpaque = -1, kAll = -2;

  // Clears `gbuffer` and draws `scene` (uploaded as `gpu`) into it, seen through `view`,
  // the ambient radiance `ambient` added to every lit surface: the draws `only` names
  // (kOpaque, kAll), or draw `only` alone over the depth the G-buffer holds (the colour
  // targets cleared, the depth kept).
  void draw(const Scene& scene, const GpuScene& gpu, const GBuffer& gbuffer, const View& view,
            glm::vec3 ambient, int only = kOpaque) const;

 private:
  struct SlotUniforms {
    GLint bound, secondSet, transform;
  };
  void setMaterial(const Material& m, const GpuScene& gpu, const GpuScene::Draw& d) const;

  Aov aov_;
  const gl::Program& program_;  // kept by the context
  GLint viewProjection_, ambient_, model_, normalMatrix_, baseColorFactor_, metallic_, roughness_,
      emissive_, normalScale_, occlusionStrength_, alphaCutoff_, unlit_, opaque_, doubleSided_,
      mirrored_, pointSize_, specularGlossiness_, specularFactor_, glossiness_;
  std::array<SlotUniforms, Material::kTextureSlots> slots_;
};

}  // namespace manylight
