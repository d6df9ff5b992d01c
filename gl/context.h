#pragma once
// A headless OpenGL 3.3 core context, made current on the calling thread. One
// implementation per platform: gl/context_osmesa.cpp and gl/context_egl.cpp.
#include <memory>
#include <string>
#include <vector>

#include "scene/error.h"

namespace manylight::gl {

// Thrown by gl/ when no context can be had or the driver fails.
class GlError : public Error {
 public:
  using Error::Error;
};

enum class Backend { Auto, Egl, OSMesa };

// "auto", "egl", "osmesa" → Backend; throws GlError for anything else.
Backend parseBackend(const std::string& name);

class Context {
 public:
  virtual ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // What was created: "egl-device", "egl-surfaceless" or "osmesa".
  const std::string& backend() const { return backend_; }
  // GL_RENDERER and GL_VERSION of the current context.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }

 protected:
  explicit Context(std::string backend) : backend_(std::move(backend)) {}
  // Loads the GL functions and checks for 3.3 core; throws GlError naming what is missing.
  void finishSetup(void* (*getProcAddress)(const char*));

 private:
  std::string backend_, renderer_, version_;
};

// Creates a context. Auto tries EGL device → EGL surfaceless (Mesa) → OSMesa and keeps
// the first that works; each attempt's outcome is appended to `attempts` (for --verbose).
// Throws GlError with every attempt's reason when none works.
std::unique_ptr<Context> createContext(Backend backend, std::vector<std::string>* attempts = nullptr);

// One per platform file.
std::unique_ptr<Context> createOSMesaContext();
std::unique_ptr<Context> createEglDeviceContext();
std::unique_ptr<Context> createEglSurfacelessContext();

}  // namespace manylight::gl
