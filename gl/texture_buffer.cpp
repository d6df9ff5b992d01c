#include "gl/texture_buffer.h"

#include <algorithm>

#include "gl/context.h"

namespace manylight::gl {

using namespace api;

std::size_t maxTextureBufferTexels() {
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  return std::size_t(std::max(maxTexels, 0));
}

TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what) {
  const std::size_t maxTexels = maxTextureBufferTexels();
  if (texels > maxTexels) {
    throw GlError(what + " need " + std::to_string(texels) +
                  " texels, the driver's texture buffers hold " + std::to_string(maxTexels));
  }
  TextureBuffer t;
  glBindBuffer(GL_TEXTURE_BUFFER, t.buffer.id());
  const std::size_t bytes = format == GL_R32UI                             ? 4
                            : format == GL_RG32UI || format == GL_RGBA16UI ? 8
                                                                           : 16;
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(texels * bytes), data, GL_STATIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, t.texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, format, t.buffer.id());
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  return t;
}

}  // namespace manylight::gl
