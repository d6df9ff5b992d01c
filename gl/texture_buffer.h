#pragma once
// A buffer texture (samplerBuffer) filled from memory.
#include <cstddef>
#include <functional>
#include <string>

#include "gl/objects.h"

namespace manylight::gl {

struct TextureBuffer {
  Buffer buffer;
  Texture texture;
  std::size_t bytes = 0;  // the buffer's size
};

// The most texels a texture buffer holds on this context (GL_MAX_TEXTURE_BUFFER_SIZE).
std::size_t maxTextureBufferTexels();

// Uploads `texels` texels of `format` (GL_RGBA32F, GL_RGBA32UI: 16 bytes; GL_RG32UI,
// GL_RGBA16UI: 8; GL_R32UI: 4) from `data`.
// Throws GlError naming `what` when the driver's texture buffers are too small.
TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what);

// Fills `t` with `texels` texels of `format`, which `write` writes through a pointer to the
// buffer's mapped memory: no copy of them is made first (cuts/cut_texels.h says why that
// matters). Keeps t's buffer where it holds as many already (texels past `texels` keep what
// they held: the shader must not read them), else makes a new one, as large.
// `write` must not throw (the buffer is mapped while it runs). Throws GlError naming `what`
// when the driver's texture buffers are too small or the mapping fails.
void fillTextureBuffer(TextureBuffer& t, std::size_t texels, GLenum format,
                       const std::function<void(void*)>& write, const std::string& what);

}  // namespace manylight::gl
