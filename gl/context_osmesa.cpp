// OSMesa: Mesa's off-screen software renderer (llvmpipe), needs no display or device.
//
// libOSMesa is opened when an OSMesa context is asked for, not linked: it pulls in LLVM
// (about 120 MB), which a machine that renders through an EGL device never needs, and a
// machine without it still runs every other backend. <GL/osmesa.h> gives the types only.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <string>
#include <type_traits>

#include "gl/context.h"

namespace manylight::gl {
namespace {

// The four entry points we call, from the library Debian's libosmesa6 installs.
struct OSMesaApi {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
};

// Opens libOSMesa once per process and keeps it open; throws GlError naming what failed.
const OSMesaApi& osmesaApi() {
  static const OSMesaApi api = [] {
    constexpr const char* kLibrary = "libOSMesa.so.8";
    void* handle = dlopen(kLibrary, RTLD_LAZY | RTLD_LOCAL);
    if (!handle) throw GlError(std::string("osmesa: cannot load ") + dlerror());
    OSMesaApi a;
    auto bind = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
      if (!fn) throw GlError(std::string("osmesa: ") + kLibrary + " has no " + name);
    };
    bind(a.createContextAttribs, "OSMesaCreateContextAttribs");
    bind(a.makeCurrent, "OSMesaMakeCurrent");
    bind(a.destroyContext, "OSMesaDestroyContext");
    bind(a.getProcAddress, "OSMesaGetProcAddress");
    return a;
  }();
  return api;
}

void* osmesaProc(const char* name) {
  return reinterpret_cast<void*>(osmesaApi().getProcAddress(name));
}

class OSMesaContextImpl final : public Context {
 public:
  OSMesaContextImpl() : Context("osmesa"), api_(osmesaApi()) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    ctx_ = api_.createContextAttribs(attribs, nullptr);
    if (!ctx_) {
      throw GlError("osmesa: OSMesaCreateContextAttribs failed for a 3.3 core profile");
    }
    // We render into our own framebuffer objects; OSMesa still wants a colour buffer.
    if (!api_.makeCurrent(ctx_, buffer_.data(), 0x1401 /* GL_UNSIGNED_BYTE */, 1, 1)) {
      api_.destroyContext(ctx_);
      throw GlError("osmesa: OSMesaMakeCurrent failed");
    }
    try {
      finishSetup(osmesaProc);
    } catch (...) {
      api_.destroyContext(ctx_);
      throw;
    }
  }
  ~OSMesaContextImpl() override {
    releasePrograms();
    api_.makeCurrent(nullptr, nullptr, 0, 0, 0);
    api_.destroyContext(ctx_);
  }

 private:
  const OSMesaApi& api_;
  OSMesaContext ctx_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

std::unique_ptr<Context> createOSMesaContext() { return std::make_unique<OSMesaContextImpl>(); }

}  // namespace manylight::gl
