#pragma once
// A headless OpenGL 3.3 core context, made current on the calling thread. One
// implementation per platform: gl/context_osmesa.cpp and gl/context_egl.cpp.
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace manylight::gl {

// Thrown by gl/ when no context can be had or the driver fails.
class GlError : public Error {
 public:
  using Error::Error;
};

enum class Backend { Auto, Egl, OSMesa };

class Program;

// "auto", "egl", "osmesa" → Backend; throws GlError for anything else.
Backend parseBackend(const std::string& name);

class Context {
 public:
  virtual ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // What was created: "egl-device", "egl-surfaceless" or "osmesa".
  const std::string& backend() const { return backend_; }
  // GL_RENDERER and GL_VERSION of the current context.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }

  // The program of gl::Program's constructor, compiled once per context and kept until the
  // context ends, so renderers created one after another (a batch of thumbnails) do not
  // compile the same variant again. Throws GlError.
  const Program& program(std::string_view vertex, std::string_view fragment,
                         const std::vector<std::string>& defines,
                         const std::vector<std::string>& outputs);

  // The context created last and still alive (a process has one), or null.
  static Context* current();

 protected:
  explicit Context(std::string backend);
  // Loads the GL functions and checks for 3.3 core; throws GlError naming what is missing.
  void finishSetup(void* (*getProcAddress)(const char*));
  // Deletes the cached programs; each platform's destructor calls it while still current.
  void releasePrograms();

 private:
  std::string backend_, renderer_, version_;
  std::map<std::string, std::unique_ptr<Program>> programs_;
};

// Context::current()->program(...); throws GlError when there is no context.
const Program& cachedProgram(std::string_view vertex, std::string_view fragment,
                             const std::vector<std::string>& defines,
                             const std::vector<std::string>& outputs);

// Creates a context. Auto tries EGL device → EGL surfaceless (Mesa) → OSMesa and keeps
// the first that works; each attempt's outcome is appended to `attempts` (for --verbose).
// Throws GlError with every attempt's reason when none works.
std::unique_ptr<Context> createContext(Backend backend,
                                       std::vector<std::string>* attempts = nullptr);

// One per platform file.
std::unique_ptr<Context> createOSMesaContext();
std::unique_ptr<Context> createEglDeviceContext();
std::unique_ptr<Context> createEglSurfacelessContext();

}  // namespace manylight::gl
