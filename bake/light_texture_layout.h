#pragma once
// Layout of the light texture: the one place that says where each light parameter lives.
// bake/light_pack.cpp writes it; glsl/light_texture.glsl reads it. Change both together.
//
// Format: a GL_RGBA32F texture buffer (samplerBuffer), kTexelsPerLight texels per light,
// light i at texels kTexelsPerLight·i + 0, 1, 2:
//
//   texel 0  .xyz  point, spot: world position
//                  directional: unit vector from the surface towards the light (−direction)
//            .w    point, spot: 1/range² (0: no range);  directional: −1
//   texel 1  .xyz  spot: unit axis, the way the light travels; point, directional: 0
//            .w    cone scale  = 1 / max(cos inner − cos outer, kMinConeWidth); else 0
//   texel 2  .rgb  colour · intensity (linear RGB; candela or lux)
//            .w    cone offset = −cos outer · cone scale; else 1
//
// Lights are ordered by type: all directional lights, then all point lights, then all spot
// lights (packLights reports where each group starts), so the shader runs one loop per type
// and evaluates only what that type needs.
//
// With l the unit vector towards the light, cone(l) = t²(3 − 2t) where
// t = clamp(dot(−l, axis) · scale + offset, 0, 1): the smoothstep of scene/shading_model.h,
// and exactly 1 for point and directional lights.
namespace manylight::layout {

inline constexpr int kTexelsPerLight = 3;
inline constexpr int kFloatsPerLight = kTexelsPerLight * 4;
inline constexpr float kDirectionalMarker = -1.0f;

}  // namespace manylight::layout
