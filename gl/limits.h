#pragma once
// The current context's limits on the size of what it renders to: a render's targets are
// textures of the image's size, drawn through a viewport of that size.
#include <string>

namespace manylight::gl {

struct RenderSizeLimits {
  int maxTextureSize = 0;       // GL_MAX_TEXTURE_SIZE
  int maxRenderbufferSize = 0;  // GL_MAX_RENDERBUFFER_SIZE
  int maxViewportWidth = 0;     // GL_MAX_VIEWPORT_DIMS
  int maxViewportHeight = 0;
};

// The current context's limits. Needs a current context.
RenderSizeLimits renderSizeLimits();

// Empty when the current context can render width × height; otherwise the first limit
// exceeded, as "exceeds the context's GL_MAX_TEXTURE_SIZE 8192" (texture size, then
// renderbuffer size, then viewport). Needs a current context.
std::string renderSizeExceeded(int width, int height);

}  // namespace manylight::gl
