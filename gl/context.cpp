#include "gl/context.h"

#include "gl/api.h"

namespace manylight::gl {

using namespace api;

Backend parseBackend(const std::string& name) {
  if (name == "auto") return Backend::Auto;
  if (name == "egl") return Backend::Egl;
  if (name == "osmesa") return Backend::OSMesa;
  throw GlError("unknown backend '" + name + "', expected auto, egl or osmesa");
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
