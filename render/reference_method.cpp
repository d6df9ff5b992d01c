#include "render/reference_method.h"

#include <algorithm>

#include "gl/context.h"
#include "glsl/variants.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

std::vector<std::string> ReferenceMethod::variant(const GpuScene& scene) {
  return glsl::referenceDefines(
      (scene.pointStart() > 0 ? glsl::kReferenceHasDirectional : 0u) |
      (scene.spotStart() > scene.pointStart() ? glsl::kReferenceHasPoint : 0u) |
      (scene.lightCount() > scene.spotStart() ? glsl::kReferenceHasSpot : 0u) |
      (scene.hasSpecular() ? glsl::kReferenceHasSpecular : 0u));
}

const gl::Program& ReferenceMethod::program(const std::vector<std::string>& defines) const {
  return gl::cachedProgram("fullscreen.vert", "lighting_reference.frag", defines, {"oRadiance"});
}

int ReferenceMethod::lightsPerPass(int pixels) {
  return int(
      std::clamp<long long>(kEvaluationsPerPass / std::max(pixels, 1), 1, kMaxLightsPerPass));
}

int ReferenceMethod::light(const GpuScene& scene, const GBuffer& gbuffer, const View& view,
                           int perPass) const {
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.lightingFramebuffer().id());
  const gl::Program& shader = program(variant(scene));
  shader.use();
  bindLightingInputs(shader, gbuffer, scene, view);

  if (perPass <= 0) perPass = lightsPerPass(gbuffer.width() * gbuffer.height());
  perPass = std::min(perPass, kMaxLightsPerPass);
  int passes = 0;
  for (int first = 0; first < scene.lightCount(); first += perPass) {
    glUniform1i(shader.uniform("uFirstLight"), first);
    glUniform1i(shader.uniform("uLightCount"), std::min(perPass, scene.lightCount() - first));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++passes;
  }
  glDisable(GL_BLEND);
  glActiveTexture(GL_TEXTURE0);
  return passes;
}

}  // namespace manylight
