#include "render/gbuffer.h"

#include <cstdio>
#include <string>

#include "gl/context.h"
#include "gl/limits.h"

namespace manylight {

using namespace gl::api;

void allocateTarget(const gl::Texture& t, GLint internal, GLenum format, GLenum type, int w,
                    int h) {
  glBindTexture(GL_TEXTURE_2D, t.id());
  glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

namespace {

void checkComplete(const char* which) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char message[96];
    std::snprintf(message, sizeof message, "%s framebuffer is incomplete (status 0x%04X)", which,
                  unsigned(status));
    throw gl::GlError(message);
  }
}

}  // namespace

GBuffer::GBuffer(int width, int height) : width_(width), height_(height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string exceeded = gl::renderSizeExceeded(width, height);
  if (!exceeded.empty()) throw gl::GlError("image size " + size + " " + exceeded);
  for (const gl::Texture& t : targets_)
    allocateTarget(t, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
  allocateTarget(depth_, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width, height);
  glBindTexture(GL_TEXTURE_2D, 0);
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    // Within the limits a driver may still refuse the memory: 84 bytes a pixel.
    const double mib = double(width) * height * (kTargetCount * 16 + 4) / (1 << 20);
    char message[160];
    std::snprintf(message, sizeof message,
                  "image size %s: the driver cannot allocate the G-buffer's %.0f MiB (OpenGL "
                  "error 0x%04X)",
                  size.c_str(), mib, unsigned(error));
    throw gl::GlError(message);
  }

  glBindFramebuffer(GL_FRAMEBUFFER, geometry_.id());
  GLenum buffers[kTargetCount];
  for (int i = 0; i < kTargetCount; ++i) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D,
                           targets_[i].id(), 0);
    buffers[i] = GL_COLOR_ATTACHMENT0 + i;
  }
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.id(), 0);
  glDrawBuffers(kTargetCount, buffers);
  checkComplete("G-buffer");

  glBindFramebuffer(GL_FRAMEBUFFER, lighting_.id());
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                         targets_[kRadiance].id(), 0);
  const GLenum one = GL_COLOR_ATTACHMENT0;
  glDrawBuffers(1, &one);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  checkComplete("lighting");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<float> GBuffer::read(Target t) const {
  std::vector<float> out;
  read(t, out);
  return out;
}

void GBuffer::read(Target t, std::vector<float>& out) const {
  out.resize(std::size_t(width_) * height_ * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, geometry_.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadBuffer(GL_COLOR_ATTACHMENT0 + t);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, out.data());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace manylight
