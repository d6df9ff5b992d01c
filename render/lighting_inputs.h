#pragma once
// What every lighting pass reads: the G-buffer targets, the light texture and the eye.
#include "gl/objects.h"
#include "render/gbuffer.h"
#include "render/gpu_scene.h"
#include "scene/camera.h"

namespace manylight {

// Binds the lighting framebuffer state (additive blending into the radiance target), the
// G-buffer targets to units 0–3 and the light texture to unit 4, and sets the uniforms of
// glsl/shading.glsl and glsl/light_texture.glsl on `program`, which must be in use.
void bindLightingInputs(const gl::Program& program, const GBuffer& gbuffer, const GpuScene& scene,
                        const View& view);

}  // namespace manylight
