#pragma once
// The classes of the camera's pixels (PixelClass, render/light_caches.h) as a stencil, so each
// per-pixel pass of `--indirect caches` (glsl/cache_near.frag, glsl/cache_interpolate.frag)
// runs only on the pixels that need it. llvmpipe runs every instruction of a shader for a
// block of pixels whenever one pixel of it does: a branch's body, a loop's first iteration,
// and the rest of a discarded pixel's shader too. A stencil test that fails for a whole block
// skips the shader there. The CPU classifies the pixels anyway when it allocates the caches
// (allocateCaches), so the classes come from there, uploaded once a frame.
// No pass writes the stencil (glStencilMask(0)): llvmpipe then tests it before the shader
// even where the shader may discard; with a stencil it may write, a discarding shader runs
// first and is tested after (the near field took 4× as long so).
#include <cstdint>
#include <vector>

#include "gl/objects.h"
#include "render/gbuffer.h"

namespace manylight {

class PixelClasses {
 public:
  PixelClasses() = default;
  // Uploads per pixel of `camera` its classes (rows bottom-up, as GBuffer::read gives them).
  // Throws gl::GlError.
  void upload(const GBuffer& camera, const std::vector<std::uint8_t>& classes);
  // As bindIndirectInputs, into `camera`'s radiance target with the classes as its stencil:
  // only the pixels whose classes masked by `mask` are `bits` are drawn, until done().
  void bind(const gl::Program& program, const GBuffer& camera, unsigned bits, unsigned mask) const;
  static void done();

 private:
  gl::Texture stencil_;                // DEPTH24_STENCIL8: the classes in the stencil
  std::vector<std::uint32_t> texels_;  // its texels, kept for their memory
  gl::Framebuffer framebuffer_;
  int width_ = 0, height_ = 0;  // of stencil_, once its framebuffer was complete
};

}  // namespace manylight
