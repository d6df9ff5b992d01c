// EGL without a window: an EGL device (a GPU, or Mesa's software device) or Mesa's
// surfaceless platform. The context renders only into framebuffer objects.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "gl/context.h"

namespace manylight::gl {
namespace {

std::string eglErrorName() {
  const EGLint e = eglGetError();
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04X", unsigned(e));
      return buf;
    }
  }
}

void* eglProc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + n, name)) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

class EglContextImpl final : public Context {
 public:
  EglContextImpl(const std::string& backend, EGLDisplay display)
      : Context(backend), display_(display) {
    const std::string where = backend + ": ";
    if (display_ == EGL_NO_DISPLAY)
      throw GlError(where + "no EGL display (" + eglErrorName() + ")");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) {
      throw GlError(where + "eglInitialize failed (" + eglErrorName() + ")");
    }
    try {
      create(where);
    } catch (...) {
      release();
      throw;
    }
  }
  ~EglContextImpl() override {
    releasePrograms();
    release();
  }

 private:
  void create(const std::string& where) {
    if (!eglBindAPI(EGL_OPENGL_API)) {
      throw GlError(where + "eglBindAPI(EGL_OPENGL_API) failed (" + eglErrorName() + ")");
    }
    const char* exts = eglQueryString(display_, EGL_EXTENSIONS);
    if (!hasExtension(exts, "EGL_KHR_surfaceless_context")) {
      throw GlError(where + "EGL_KHR_surfaceless_context is not supported");
    }
    EGLConfig config = nullptr;
    if (!hasExtension(exts, "EGL_KHR_no_config_context")) {
      const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint count = 0;
      if (!eglChooseConfig(display_, want, &config, 1, &count) || count < 1) {
        throw GlError(where + "no EGL config for OpenGL (" + eglErrorName() + ")");
      }
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              3,
                              EGL_CONTEXT_MINOR_VERSION,
                              3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT) {
      throw GlError(where + "eglCreateContext for OpenGL 3.3 core failed (" + eglErrorName() + ")");
    }
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw GlError(where + "eglMakeCurrent failed (" + eglErrorName() + ")");
    }
    finishSetup(eglProc);
  }

  void release() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    context_ = EGL_NO_CONTEXT;
    eglTerminate(display_);
  }

  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

template <typename Fn>
Fn clientProc(const char* name, const std::string& backend) {
  auto fn = reinterpret_cast<Fn>(eglGetProcAddress(name));
  if (!fn) throw GlError(backend + ": " + std::string(name) + " is not available");
  return fn;
}

}  // namespace

std::unique_ptr<Context> createEglDeviceContext() {
  const std::string backend = "egl-device";
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExts, "EGL_EXT_device_enumeration") &&
      !hasExtension(clientExts, "EGL_EXT_device_base")) {
    throw GlError(backend + ": EGL_EXT_device_enumeration is not supported");
  }
  auto queryDevices = clientProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT", backend);
  auto queryString = clientProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT", backend);
  auto getDisplay =
      clientProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT", backend);
  EGLint count = 0;
  if (!queryDevices(0, nullptr, &count) || count <= 0) {
    throw GlError(backend + ": no EGL devices (" + eglErrorName() + ")");
  }
  std::vector<EGLDeviceEXT> devices(count);
  queryDevices(count, devices.data(), &count);
  // Hardware devices (with a DRM node) first, then software ones.
  std::vector<EGLDeviceEXT> ordered;
  for (int pass = 0; pass < 2; ++pass) {
    for (EGLDeviceEXT d : devices) {
      const bool drm = hasExtension(queryString(d, EGL_EXTENSIONS), "EGL_EXT_device_drm");
      if (drm == (pass == 0)) ordered.push_back(d);
    }
  }
  std::string reasons;
  for (EGLDeviceEXT d : ordered) {
    try {
      return std::make_unique<EglContextImpl>(backend,
                                              getDisplay(EGL_PLATFORM_DEVICE_EXT, d, nullptr));
    } catch (const GlError& e) {
      reasons += (reasons.empty() ? "" : "; ") + std::string(e.what());
    }
  }
  throw GlError(reasons.empty() ? backend + ": no usable EGL device" : reasons);
}

std::unique_ptr<Context> createEglSurfacelessContext() {
  const std::string backend = "egl-surfaceless";
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    throw GlError(backend + ": EGL_MESA_platform_surfaceless is not supported");
  }
  auto getDisplay =
      clientProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT", backend);
  return std::make_unique<EglContextImpl>(
      backend, getDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
}

}  // namespace manylight::gl
