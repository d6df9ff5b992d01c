#include "render/reference_method.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

namespace manylight {

using namespace gl::api;

std::vector<std::string> ReferenceMethod::variant(const GpuScene& scene) {
  std::vector<std::string> defines;
  if (scene.pointStart() > 0) defines.push_back("HAS_DIRECTIONAL");
  if (scene.spotStart() > scene.pointStart()) defines.push_back("HAS_POINT");
  if (scene.lightCount() > scene.spotStart()) defines.push_back("HAS_SPOT");
  if (scene.hasSpecular()) defines.push_back("HAS_SPECULAR");
  return defines;
}

const gl::Program& ReferenceMethod::program(const std::vector<std::string>& defines) const {
  auto it = programs_.find(defines);
  if (it == programs_.end()) {
    it = programs_.emplace(defines, gl::Program("fullscreen.vert", "lighting_reference.frag", defines,
                                                {"oRadiance"})).first;
  }
  return it->second;
}

int ReferenceMethod::lightsPerPass(int pixels) {
  return int(std::clamp<long long>(kEvaluationsPerPass / std::max(pixels, 1), 1, 1 << 20));
}

int ReferenceMethod::light(const GpuScene& scene, const GBuffer& gbuffer, const View& view,
                           int perPass) const {
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.lightingFramebuffer().id());
  glViewport(0, 0, gbuffer.width(), gbuffer.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  const gl::Program& shader = program(variant(scene));
  shader.use();
  const GBuffer::Target inputs[] = {GBuffer::kPosition, GBuffer::kNormal, GBuffer::kAlbedo,
                                    GBuffer::kSpecular};
  const char* names[] = {"uPosition", "uNormal", "uAlbedo", "uSpecular"};
  for (int i = 0; i < 4; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, gbuffer.target(inputs[i]).id());
    glUniform1i(shader.uniform(names[i]), i);
  }
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_BUFFER, scene.lightTexture().id());
  glUniform1i(shader.uniform("uLights"), 4);
  glUniform3fv(shader.uniform("uEye"), 1, glm::value_ptr(view.eye));
  glUniform3fv(shader.uniform("uForward"), 1, glm::value_ptr(view.forward));
  glUniform1i(shader.uniform("uOrthographic"), view.orthographic ? 1 : 0);
  glUniform1i(shader.uniform("uPointStart"), scene.pointStart());
  glUniform1i(shader.uniform("uSpotStart"), scene.spotStart());

  if (perPass <= 0) perPass = lightsPerPass(gbuffer.width() * gbuffer.height());
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
