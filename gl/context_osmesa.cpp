// OSMesa: Mesa's off-screen software renderer (llvmpipe), needs no display or device.
#include <GL/osmesa.h>

#include <array>

#include "gl/context.h"

namespace manylight::gl {
namespace {

void* osmesaProc(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

class OSMesaContextImpl final : public Context {
 public:
  OSMesaContextImpl() : Context("osmesa") {
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
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) {
      throw GlError("osmesa: OSMesaCreateContextAttribs failed for a 3.3 core profile");
    }
    // We render into our own framebuffer objects; OSMesa still wants a colour buffer.
    if (!OSMesaMakeCurrent(ctx_, buffer_.data(), 0x1401 /* GL_UNSIGNED_BYTE */, 1, 1)) {
      OSMesaDestroyContext(ctx_);
      throw GlError("osmesa: OSMesaMakeCurrent failed");
    }
    try {
      finishSetup(osmesaProc);
    } catch (...) {
      OSMesaDestroyContext(ctx_);
      throw;
    }
  }
  ~OSMesaContextImpl() override {
    releasePrograms();
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(ctx_);
  }

 private:
  OSMesaContext ctx_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

std::unique_ptr<Context> createOSMesaContext() { return std::make_unique<OSMesaContextImpl>(); }

}  // namespace manylight::gl
