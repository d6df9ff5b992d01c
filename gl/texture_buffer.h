#pragma once
// A buffer texture (samplerBuffer) filled once from memory.
#include <cstddef>
#include <string>

#include "gl/objects.h"

namespace manylight::gl {

struct TextureBuffer {
  Buffer buffer;
  Texture texture;
};

// Uploads `texels` texels of 16 bytes (`format`: GL_RGBA32F or GL_RGBA32UI) from `data`.
// Throws GlError naming `what` when the driver's texture buffers are too small.
TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what);

}  // namespace manylight::gl
