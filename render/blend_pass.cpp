#include "render/blend_pass.h"

#include <algorithm>
#include <vector>

#include "gl/context.h"

namespace manylight {

using namespace gl::api;

namespace {

void blit(GLuint from, GLuint to, int w, int h, GLbitfield mask) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, mask, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace

BlendPass::BlendPass(int width, int height)
    : width_(width),
      height_(height),
      program_(gl::cachedProgram("fullscreen.vert", "blend_composite.frag", {}, {"oColour"})) {
  allocateTarget(savedDepth_, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width, height);
  allocateTarget(composite_, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLenum none = GL_NONE, colour = GL_COLOR_ATTACHMENT0;
  glBindFramebuffer(GL_FRAMEBUFFER, depthFramebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, savedDepth_.id(), 0);
  glDrawBuffers(1, &none);
  glReadBuffer(GL_NONE);
  glBindFramebuffer(GL_FRAMEBUFFER, compositeFramebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, composite_.id(), 0);
  glDrawBuffers(1, &colour);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  for (GLuint fb : {depthFramebuffer_.id(), compositeFramebuffer_.id()}) {
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("the blend pass's framebuffers are incomplete");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  radiance_ = program_.uniform("uRadiance");
  albedo_ = program_.uniform("uAlbedo");
}

void BlendPass::draw(const Scene& scene, const GpuScene& gpu, const GBuffer& gbuffer,
                     const View& view, glm::vec3 ambient, const GeometryPass& geometry,
                     const std::function<void()>& light) const {
  const std::vector<GpuScene::Draw>& draws = gpu.draws();
  std::vector<int> order;
  for (std::size_t i = 0; i < draws.size(); ++i) {
    if (draws[i].blended) order.push_back(int(i));
  }
  if (order.empty()) return;
  // Farthest first: by distance from the eye, or along the view for orthographic views.
  auto depth = [&](int i) {
    const glm::vec3 c = draws[std::size_t(i)].centre;
    return view.orthographic ? glm::dot(c - view.eye, view.forward) : glm::length(c - view.eye);
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return depth(a) > depth(b); });

  const GLuint geometryFb = gbuffer.geometryFramebuffer().id();
  const GLuint lightingFb = gbuffer.lightingFramebuffer().id();
  blit(geometryFb, depthFramebuffer_.id(), width_, height_, GL_DEPTH_BUFFER_BIT);
  blit(lightingFb, compositeFramebuffer_.id(), width_, height_, GL_COLOR_BUFFER_BIT);
  for (int i : order) {
    blit(depthFramebuffer_.id(), geometryFb, width_, height_, GL_DEPTH_BUFFER_BIT);
    geometry.draw(scene, gpu, gbuffer, view, ambient, i);
    light();
    glBindFramebuffer(GL_FRAMEBUFFER, compositeFramebuffer_.id());
    glViewport(0, 0, width_, height_);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    program_.use();
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, gbuffer.target(GBuffer::kRadiance).id());
    glUniform1i(radiance_, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, gbuffer.target(GBuffer::kAlbedo).id());
    glUniform1i(albedo_, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
  }
  blit(compositeFramebuffer_.id(), lightingFb, width_, height_, GL_COLOR_BUFFER_BIT);
}

}  // namespace manylight
