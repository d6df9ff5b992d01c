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

// Fills the buffer bound to `target` with `bytes` bytes from `data` (GL_STATIC_DRAW). Large
// ones go through a mapping, copied on all cores: the driver's own copy runs on one thread,
// which takes every page fault of the new storage. Throws GlError naming `what` when the
// driver cannot map the buffer or loses its contents.
void copyIntoBuffer(GLenum target, const void* data, std::size_t bytes, const std::string& what);

// Uploads `texels` texels of `format` (GL_RGBA32F, GL_RGBA32UI: 16 bytes; GL_RG32UI,
// GL_RGBA16UI: 8; GL_R32UI: 4) from `data`.
// Throws GlError naming `what` when the driver's texture buffers are too small.
TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what);

}  // namespace manylight::gl
