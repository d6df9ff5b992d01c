#include "gl/context.h"

#include "gl/api.h"
#include "gl/objects.h"

namespace manylight::gl {

using namespace api;

Backend parseBackend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "egl") return Backend::Egl;
  if (name == "osmesa") return Backend::OSMesa;
  throw GlError("unknown backend '" + name + "', expected auto, egl or osmesa");
}

namespace {
Context* gCurrent = nullptr;
}  // namespace

Context::Context(std::string backend) : backend_(std::move(backend)) {}

Context::~Context() {
  if (gCurrent == this) gCurrent = nullptr;
}

Context* Context::current() { return gCurrent; }

void Context::releasePrograms() { programs_.clear(); }

const Program& Context::program(std::string_view vertex, std::string_view fragment,
                                const std::vector<std::string>& defines,
                                const std::vector<std::string>& outputs) {
  std::string key = std::string(vertex) + "|" + std::string(fragment);
  for (const std::string& d : defines) key += "|" + d;
  key += "|>";
  for (const std::string& o : outputs) key += "|" + o;
  std::unique_ptr<Program>& slot = programs_[key];
  if (!slot) {
    try {
      slot = std::make_unique<Program>(vertex, fragment, defines, outputs);
    } catch (...) {
      programs_.erase(key);
      throw;
    }
  }
  return *slot;
}

const Program& cachedProgram(std::string_view vertex, std::string_view fragment,
                             const std::vector<std::string>& defines,
                             const std::vector<std::string>& outputs) {
  if (!gCurrent) throw GlError("no OpenGL context to compile " + std::string(fragment) + " in");
  return gCurrent->program(vertex, fragment, defines, outputs);
}

void Context::finishSetup(void* (*getProcAddress)(const char*)) {
  const std::string missing = loadApi(getProcAddress);
  auto str = [](GLenum e) {
    const GLubyte* s = api::glGetString ? api::glGetString(e) : nullptr;
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("unknown");
  };
  renderer_ = str(GL_RENDERER);
  version_ = str(GL_VERSION);
  if (!missing.empty()) {
    throw GlError(backend_ + ": " + missing + " is missing (GL_RENDERER " + renderer_ + ")");
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 33) {
    throw GlError(backend_ + ": OpenGL 3.3 core is required, got " + version_ + " (GL_RENDERER " +
                  renderer_ + ")");
  }
  gCurrent = this;
}

std::unique_ptr<Context> createContext(Backend backend, std::vector<std::string>* attempts) {
  using Factory = std::unique_ptr<Context> (*)();
  struct Option {
    const char* name;
    Factory create;
  };
  std::vector<Option> options;
  if (backend != Backend::OSMesa) {
    options.push_back({"egl-device", createEglDeviceContext});
    options.push_back({"egl-surfaceless", createEglSurfacelessContext});
  }
  if (backend != Backend::Egl) options.push_back({"osmesa", createOSMesaContext});
  std::string reasons;
  for (const Option& o : options) {
    try {
      auto ctx = o.create();
      if (attempts) attempts->push_back(std::string(o.name) + ": ok (" + ctx->renderer() + ")");
      return ctx;
    } catch (const GlError& e) {
      if (attempts) attempts->push_back(std::string(o.name) + ": " + e.what());
      reasons += (reasons.empty() ? "" : "; ") + std::string(e.what());
    }
  }
  throw GlError("no OpenGL 3.3 core context: " + reasons);
}

}  // namespace manylight::gl
