#include "render/pixel_classes.h"

#include "gl/context.h"
#include "render/lighting_inputs.h"

namespace manylight {

using namespace gl::api;

void PixelClasses::upload(const GBuffer& camera, const std::vector<std::uint8_t>& classes) {
  const bool sized = width_ == camera.width() && height_ == camera.height();
  // GL_UNSIGNED_INT_24_8: depth in the upper 24 bits (unused), the stencil in the lower 8.
  texels_.assign(std::size_t(camera.width()) * std::size_t(camera.height()), 0);
  for (std::size_t i = 0; i < texels_.size() && i < classes.size(); ++i) texels_[i] = classes[i];
  glBindTexture(GL_TEXTURE_2D, stencil_.id());
  if (sized) {  // into the texture's memory, not new memory
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                    texels_.data());
  } else {
    width_ = height_ = 0;  // until the framebuffer below is complete
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH24_STENCIL8, camera.width(), camera.height(), 0,
                 GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, texels_.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  // Attached every upload: cheap, and a camera's radiance target may be a new texture of an
  // old one's name.
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                         camera.target(GBuffer::kRadiance).id(), 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, stencil_.id(),
                         0);
  const GLenum one = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &one);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) throw gl::GlError("the pixel classes' framebuffer is incomplete");
  width_ = camera.width();
  height_ = camera.height();
}

void PixelClasses::bind(const gl::Program& program, const GBuffer& camera, unsigned bits,
                        unsigned mask) const {
  bindIndirectInputs(program, camera);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, GLint(bits), mask);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glStencilMask(0);
}

void PixelClasses::done() {
  glStencilMask(0xff);
  glDisable(GL_STENCIL_TEST);
}

}  // namespace manylight
