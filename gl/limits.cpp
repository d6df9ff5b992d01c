#include "gl/limits.h"

#include <algorithm>

#include "gl/api.h"

namespace manylight::gl {

using namespace api;

RenderSizeLimits renderSizeLimits() {
  RenderSizeLimits l;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.maxTextureSize);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &l.maxRenderbufferSize);
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  l.maxViewportWidth = viewport[0];
  l.maxViewportHeight = viewport[1];
  return l;
}

std::string renderSizeExceeded(int width, int height) {
  const RenderSizeLimits l = renderSizeLimits();
  const int side = std::max(width, height);
  auto exceeds = [](const char* name, const std::string& value) {
    return std::string("exceeds the context's ") + name + " " + value;
  };
  if (side > l.maxTextureSize)
    return exceeds("GL_MAX_TEXTURE_SIZE", std::to_string(l.maxTextureSize));
  if (side > l.maxRenderbufferSize)
    return exceeds("GL_MAX_RENDERBUFFER_SIZE", std::to_string(l.maxRenderbufferSize));
  if (width > l.maxViewportWidth || height > l.maxViewportHeight)
    return exceeds("GL_MAX_VIEWPORT_DIMS",
                   std::to_string(l.maxViewportWidth) + "x" + std::to_string(l.maxViewportHeight));
  return {};
}

}  // namespace manylight::gl
