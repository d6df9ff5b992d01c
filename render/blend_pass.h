#pragma once
// Blended primitives (alphaMode BLEND), drawn after the opaque frame is lit. Each blended
// draw, farthest first (by its bounds' centre), is drawn alone into the G-buffer over the
// opaque depth, lit there by the frame's own method, exactly as an opaque surface would be,
// and composited over the frame with its alpha. Its bounds: per draw only its nearest
// surface is seen (a double-sided blended sphere shows its front, not its back through it),
// and draws whose centres order differently from their pixels' depths composite in the
// centres' order (the usual sorted-transparency error). Each blended draw costs one more
// G-buffer pass and lighting pass over the pixels it covers.
#include <functional>

#include "gl/objects.h"
#include "render/gbuffer.h"
#include "render/geometry_pass.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace manylight {

class BlendPass {
 public:
  // Targets of `width` × `height` (the G-buffer's); needs a current context. Throws
  // gl::GlError.
  BlendPass(int width, int height);

  // Composites every blended draw of `gpu` over the lit frame in `gbuffer`'s radiance
  // target, lighting each with `light` (which adds the frame's method's lighting of the
  // G-buffer's pixels to its radiance target). Leaves the result in the radiance target.
  void draw(const Scene& scene, const GpuScene& gpu, const GBuffer& gbuffer, const View& view,
            glm::vec3 ambient, const GeometryPass& geometry,
            const std::function<void()>& light) const;

 private:
  int width_, height_;
  gl::Texture savedDepth_, composite_;
  gl::Framebuffer depthFramebuffer_, compositeFramebuffer_;
  const gl::Program& program_;  // kept by the context
  GLint radiance_, albedo_;
};

}  // namespace manylight
