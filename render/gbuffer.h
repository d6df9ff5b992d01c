#pragma once
// The deferred path's render targets: the G-buffer (position, normal, albedo, specular,
// depth) and the float radiance target that the G-buffer pass starts and the lighting
// passes add to.
#include <array>
#include <vector>

#include "gl/objects.h"

namespace manylight {

// Allocates `t` as a w × h render target of `internal` format, sampled NEAREST.
void allocateTarget(const gl::Texture& t, GLint internal, GLenum format, GLenum type, int w, int h);

class GBuffer {
 public:
  enum Target { kPosition, kNormal, kAlbedo, kSpecular, kRadiance, kTargetCount };

  // Throws gl::GlError naming the limit (gl/limits.h) when the context cannot render
  // width × height, when the driver cannot allocate the targets, or cannot render to these
  // formats.
  GBuffer(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  const gl::Texture& target(Target t) const { return targets_[t]; }
  const gl::Texture& depth() const { return depth_; }
  // Target `t` read back as RGBA floats, rows bottom-up (GL's order). Throws nothing.
  std::vector<float> read(Target t) const;
  // The same into `out`, resized (its memory kept where large enough).
  void read(Target t, std::vector<float>& out) const;
  // Writes all targets (the G-buffer pass).
  const gl::Framebuffer& geometryFramebuffer() const { return geometry_; }
  // Writes only the radiance target, so the lighting passes may sample the others.
  const gl::Framebuffer& lightingFramebuffer() const { return lighting_; }

 private:
  int width_, height_;
  std::array<gl::Texture, kTargetCount> targets_;
  gl::Texture depth_;
  gl::Framebuffer geometry_, lighting_;
};

}  // namespace manylight
