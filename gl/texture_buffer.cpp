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

namespace {

void checkSize(std::size_t texels, const std::string& what) {
  const std::size_t maxTexels = maxTextureBufferTexels();
  if (texels > maxTexels) {
    throw GlError(what + " need " + std::to_string(texels) +
                  " texels, the driver's texture buffers hold " + std::to_string(maxTexels));
  }
}

std::size_t bytesPerTexel(GLenum format) {
  return format == GL_R32UI ? 4 : format == GL_RG32UI || format == GL_RGBA16UI ? 8 : 16;
}

// Binds t's texture to t's buffer as `format`.
void attach(TextureBuffer& t, GLenum format) {
  glBindTexture(GL_TEXTURE_BUFFER, t.texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, format, t.buffer.id());
  glBindTexture(GL_TEXTURE_BUFFER, 0);
}

}  // namespace

TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what) {
  checkSize(texels, what);
  TextureBuffer t;
  t.bytes = texels * bytesPerTexel(format);
  glBindBuffer(GL_TEXTURE_BUFFER, t.buffer.id());
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(t.bytes), data, GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  attach(t, format);
  return t;
}

void fillTextureBuffer(TextureBuffer& t, std::size_t texels, GLenum format,
                       const std::function<void(void*)>& write, const std::string& what) {
  checkSize(texels, what);
  const std::size_t bytes = std::max<std::size_t>(texels * bytesPerTexel(format), 16);
  const bool fresh = t.bytes < bytes;
  if (fresh) t = TextureBuffer{};
  glBindBuffer(GL_TEXTURE_BUFFER, t.buffer.id());
  if (fresh) {
    glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    t.bytes = bytes;
  }
  void* mapped = glMapBufferRange(GL_TEXTURE_BUFFER, 0, GLsizeiptr(bytes),
                                  GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT);
  if (!mapped) {
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    throw GlError(what + ": mapping a buffer of " + std::to_string(bytes) + " bytes failed");
  }
  write(mapped);
  const bool kept = glUnmapBuffer(GL_TEXTURE_BUFFER) == GL_TRUE;
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  // False only where the memory was lost meanwhile (a video mode change, say).
  if (!kept) throw GlError(what + ": the buffer's contents were lost while it was mapped");
  if (fresh) attach(t, format);
}

}  // namespace manylight::gl
