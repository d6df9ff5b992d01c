#pragma once
// Move-only owners of GL objects: the destructor deletes, copying is deleted, moving is
// noexcept. Nothing outside this file calls glDelete*.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gl/api.h"

namespace manylight::gl {

template <typename Traits>
class Handle {
 public:
  Handle() : id_(Traits::create()) {}
  explicit Handle(GLenum kind) : id_(Traits::create(kind)) {}
  ~Handle() {
    if (id_) Traits::destroy(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      if (id_) Traits::destroy(id_);
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GLuint id() const { return id_; }

 private:
  GLuint id_;
};

struct TextureTraits {
  static GLuint create() {
    GLuint id = 0;
    api::glGenTextures(1, &id);
    return id;
  }
  static void destroy(GLuint id) { api::glDeleteTextures(1, &id); }
};
struct BufferTraits {
  static GLuint create() {
    GLuint id = 0;
    api::glGenBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { api::glDeleteBuffers(1, &id); }
};
struct FramebufferTraits {
  static GLuint create() {
    GLuint id = 0;
    api::glGenFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { api::glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
  static GLuint create() {
    GLuint id = 0;
    api::glGenVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { api::glDeleteVertexArrays(1, &id); }
};
struct ShaderTraits {
  static GLuint create(GLenum kind) { return api::glCreateShader(kind); }
  static void destroy(GLuint id) { api::glDeleteShader(id); }
};
struct ProgramTraits {
  static GLuint create() { return api::glCreateProgram(); }
  static void destroy(GLuint id) { api::glDeleteProgram(id); }
};

using Texture = Handle<TextureTraits>;
using Buffer = Handle<BufferTraits>;
using Framebuffer = Handle<FramebufferTraits>;
using VertexArray = Handle<VertexArrayTraits>;
using Shader = Handle<ShaderTraits>;

// A linked program with cached uniform lookups.
class Program {
 public:
  Program() = default;
  // Compiles the embedded stages `vertex` and `fragment` (names in glsl/) with `defines`
  // ("NAME VALUE" or "NAME") inserted after the #version line, binds fragment outputs in
  // the order of `outputs`, and links. Throws GlError with the driver's info log.
  Program(std::string_view vertex, std::string_view fragment,
          const std::vector<std::string>& defines, const std::vector<std::string>& outputs);

  GLuint id() const { return program_.id(); }
  void use() const { api::glUseProgram(program_.id()); }
  // The location of a uniform, or −1 if the linker removed it.
  GLint uniform(const char* name) const { return api::glGetUniformLocation(program_.id(), name); }

 private:
  Handle<ProgramTraits> program_;
};

}  // namespace manylight::gl
