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

// The most texels a texture buffer holds on this context (GL_MAX_TEXTURE_BUFFER_SIZE).
std::size_t maxTextureBufferTexels();

// Uploads `texels` texels of `format` (GL_RGBA32F, GL_RGBA32UI: 16 bytes; GL_RG32UI,
// GL_RGBA16UI: 8; GL_R32UI: 4) from `data`.
// Throws GlError naming `what` when the driver's texture buffers are too small.
TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what);

}  // namespace manylight::gl
