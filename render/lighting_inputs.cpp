#include "render/lighting_inputs.h"

#include <glm/gtc/type_ptr.hpp>

namespace manylight {

using namespace gl::api;

void bindLightingInputs(const gl::Program& program, const GBuffer& gbuffer, const GpuScene& scene,
                        const View& view) {
  glViewport(0, 0, gbuffer.width(), gbuffer.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  const GBuffer::Target inputs[] = {GBuffer::kPosition, GBuffer::kNormal, GBuffer::kAlbedo,
                                    GBuffer::kSpecular};
  const char* names[] = {"uPosition", "uNormal", "uAlbedo", "uSpecular"};
  for (int i = 0; i < 4; ++i) {
    glActiveTexture(GL_TEXTURE0 + i);
    glBindTexture(GL_TEXTURE_2D, gbuffer.target(inputs[i]).id());
    glUniform1i(program.uniform(names[i]), i);
  }
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_BUFFER, scene.lightTexture().id());
  glUniform1i(program.uniform("uLights"), 4);
  glUniform3fv(program.uniform("uEye"), 1, glm::value_ptr(view.eye));
  glUniform3fv(program.uniform("uForward"), 1, glm::value_ptr(view.forward));
  glUniform1i(program.uniform("uOrthographic"), view.orthographic ? 1 : 0);
  glUniform1i(program.uniform("uPointStart"), scene.pointStart());
  glUniform1i(program.uniform("uSpotStart"), scene.spotStart());
}

void bindSampler(const gl::Program& program, const char* name, unsigned target, unsigned id,
                 int unit) {
  glActiveTexture(GLenum(GL_TEXTURE0 + unit));
  glBindTexture(GLenum(target), GLuint(id));
  glUniform1i(program.uniform(name), unit);
}

void bindIndirectInputs(const gl::Program& program, const GBuffer& camera) {
  glBindFramebuffer(GL_FRAMEBUFFER, camera.lightingFramebuffer().id());
  glViewport(0, 0, camera.width(), camera.height());
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  bindSampler(program, "uPosition", GL_TEXTURE_2D, camera.target(GBuffer::kPosition).id(), 0);
  bindSampler(program, "uNormal", GL_TEXTURE_2D, camera.target(GBuffer::kNormal).id(), 1);
  bindSampler(program, "uAlbedo", GL_TEXTURE_2D, camera.target(GBuffer::kAlbedo).id(), 2);
}

}  // namespace manylight
