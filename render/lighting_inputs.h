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

// Binds texture `id` (of `target`, e.g. GL_TEXTURE_2D) to texture unit `unit` and points
// `program`'s sampler `name` at it.
void bindSampler(const gl::Program& program, const char* name, unsigned target, unsigned id,
                 int unit);

// What the indirect passes that add to the camera's pixels share: `camera`'s lighting
// framebuffer and viewport, additive blending, no depth test, and its position, normal and
// albedo targets on units 0–2 as uPosition, uNormal, uAlbedo of `program`, which must be in use.
void bindIndirectInputs(const gl::Program& program, const GBuffer& camera);

}  // namespace manylight
