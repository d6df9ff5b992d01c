#include "gl/context.h"
#include "gl/objects.h"
#include "glsl/shaders.h"

namespace manylight::gl {

using namespace api;

namespace {

std::string withDefines(std::string_view name, const std::vector<std::string>& defines) {
  const std::string_view text = glsl::source(name);
  if (text.empty()) throw GlError("shader " + std::string(name) + " is not embedded");
  const std::size_t eol = text.find('\n');
  std::string out(text.substr(0, eol + 1));
  for (const std::string& d : defines) out += "#define " + d + "\n";
  out += "#line 2\n";
  out += text.substr(eol + 1);
  return out;
}

Shader compile(GLenum kind, std::string_view name, const std::vector<std::string>& defines) {
  const std::string text = withDefines(name, defines);
  Shader shader(kind);
  const char* src = text.c_str();
  glShaderSource(shader.id(), 1, &src, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader.id(), sizeof log, nullptr, log);
    throw GlError("shader " + std::string(name) + " does not compile: " + log);
  }
  return shader;
}

}  // namespace

Program::Program(std::string_view vertex, std::string_view fragment,
                 const std::vector<std::string>& defines, const std::vector<std::string>& outputs) {
  const Shader vs = compile(GL_VERTEX_SHADER, vertex, defines);
  const Shader fs = compile(GL_FRAGMENT_SHADER, fragment, defines);
  glAttachShader(program_.id(), vs.id());
  glAttachShader(program_.id(), fs.id());
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    glBindFragDataLocation(program_.id(), GLuint(i), outputs[i].c_str());
  }
  glLinkProgram(program_.id());
  GLint ok = 0;
  glGetProgramiv(program_.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program_.id(), sizeof log, nullptr, log);
    throw GlError("program " + std::string(vertex) + " + " + std::string(fragment) +
                  " does not link: " + log);
  }
}

}  // namespace manylight::gl
