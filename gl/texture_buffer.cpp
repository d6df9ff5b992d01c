#include "gl/texture_buffer.h"

#include <cstring>

#include "base/parallel.h"
#include "gl/context.h"

namespace manylight::gl {

using namespace api;

namespace {

// Fewer bytes than this a thread are copied on one.
constexpr std::size_t kBytesPerThread = std::size_t(8) << 20;

}  // namespace

void copyIntoBuffer(GLenum target, const void* data, std::size_t bytes, const std::string& what) {
  if (sharesOf(bytes, kBytesPerThread) == 1) {
    glBufferData(target, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    return;
  }
  glBufferData(target, GLsizeiptr(bytes), nullptr, GL_STATIC_DRAW);
  void* const mapped = glMapBufferRange(target, 0, GLsizeiptr(bytes),
                                        GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT);
  if (!mapped)
    throw GlError(what + ": the driver could not map a buffer of " + std::to_string(bytes) +
                  " bytes");
  runOnShares(sharesOf(bytes, kBytesPerThread), bytes, [&](int, std::size_t from, std::size_t to) {
    std::memcpy(static_cast<char*>(mapped) + from, static_cast<const char*>(data) + from,
                to - from);
  });
  if (glUnmapBuffer(target) != GL_TRUE)
    throw GlError(what + ": the driver lost the buffer's contents while it was mapped");
}

TextureBuffer uploadTextureBuffer(const void* data, std::size_t texels, GLenum format,
                                  const std::string& what) {
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  if (texels > std::size_t(maxTexels)) {
    throw GlError(what + " need " + std::to_string(texels) +
                  " texels, the driver's texture buffers hold " + std::to_string(maxTexels));
  }
  TextureBuffer t;
  glBindBuffer(GL_TEXTURE_BUFFER, t.buffer.id());
  const std::size_t bytes = format == GL_R32UI                             ? 4
                            : format == GL_RG32UI || format == GL_RGBA16UI ? 8
                                                                           : 16;
  copyIntoBuffer(GL_TEXTURE_BUFFER, data, texels * bytes, what);
  glBindTexture(GL_TEXTURE_BUFFER, t.texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, format, t.buffer.id());
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  return t;
}

}  // namespace manylight::gl
