#pragma once
// manylight's shading model. glsl/shading.glsl and the CPU oracle (tests/oracle.cpp) both
// follow this file; a change here is a change there.
//
// Units follow glTF KHR_lights_punctual: point and spot intensity in candela, directional in
// lux; colours are linear RGB.
//
// Irradiance at a surface point P with unit normal N from one light, l the unit vector from P
// towards the light:
//   point, spot:  E = intensity · colour · max(N·l, 0) / d² · window(d) · cone(l)
//   directional:  E = intensity · colour · max(N·l, 0)
//   window(d) = clamp(1 − (d/range)⁴, 0, 1)    (the spec's recommendation, as the Khronos
//                                               Sample Viewer has it; no range → 1)
//   cone(l)   = smoothstep(cos outer, cos inner, −l·axis)  (spot only, axis = light direction)
//              with smoothstep(e0, e1, x) = t²(3 − 2t), t = clamp((x − e0)/(e1 − e0), 0, 1),
//              and e1 − e0 floored at kMinConeWidth so inner == outer gives a hard edge.
//
// Material (glTF metallic-roughness mapped to Lambert + normalised Phong, one formula):
//   albedo    a  = baseColour · (1 − metallic)
//   specular  ks = mix(0.04, baseColour, metallic) · (metallic + (1 − metallic)(1 − roughness))
//   exponent  n  = clamp(1/(8α²) − 1/2, 1, kMaxPhongExponent),  α = roughness²
// The exponent is chosen against GGX, which the glTF ecosystem shades with. Under a headlight
// GGX falls with the angle θ between N and H, Phong with the angle between R and V, which is
// 2θ, so 1/(2α²) would match GGX's width at its peak; but GGX's lobe has a long tail, and a
// normalised Phong lobe keeps its energy whatever n is, so a wider lobe spreads it as GGX
// does. Against the Khronos glTF Sample Viewer (headlight, mean |luma difference| over the
// gallery's metals) 1/(8α²) fit best of 1/(2α²), 1/(4α²), 1/(8α²) and 1/(16α²).
// A fully rough (roughness 1) non-metal is pure Lambert with ks = 0, the default material.
// Per pixel, from the material (scene/scene.h) and its textures, each sampled at its UV set
// through its KHR_texture_transform:
//   baseColour = baseColorFactor · baseColorTexture (decoded sRGB → linear) · COLOR_0
//   metallic   = metallicFactor · B,  roughness = roughnessFactor · G  (metallicRoughnessTexture)
//   occlusion  = 1 + strength · (R − 1)                                (occlusionTexture)
//   emissive   = emissiveFactor · emissiveStrength · emissiveTexture (decoded sRGB → linear)
//   N          = normalize(TBN · ((2·normalTexture − 1) · (scale, scale, 1))), T the tangent,
//                B = cross(N, T) · w, when a normal texture is bound; else the interpolated
//                normal. Flipped on the back of a double-sided surface.
// MASK materials discard pixels whose alpha is below alphaCutoff. KHR_materials_unlit
// materials (and points and lines without normals) show their base colour, unlit.
//
// Outgoing radiance towards the viewer V (unit, from P to the eye), R = reflect(−l, N):
//   L = ambient · (a + ks) · occlusion + emissive
//       + Σ_lights (a/π + ks · (n + 2)/(2π) · max(R·V, 0)^n) · E
// The ambient term is what a uniform environment of radiance `ambient` gives: the Lambert
// lobe reflects a of it, the normalised Phong lobe about ks (its normalisation makes the
// lobe integrate to 1 about the mirror direction, less where it dips below the horizon), so
// metals, whose a is 0, are lit by it too.
// No shadows: every light is visible from every point (as in the design documents).
// Double-sided materials shade back faces with the flipped normal; single-sided back faces
// are culled.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace manylight::shading {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDielectricF0 = 0.04;
inline constexpr double kMaxPhongExponent = 8192.0;
inline constexpr double kMinConeWidth = 1e-4;
// Squared distances are floored here so a point exactly at a light stays finite.
inline constexpr double kMinDistanceSquared = 1e-12;

struct PhongMaterial {
  glm::dvec3 albedo;
  glm::dvec3 specular;
  double exponent;
};

// Maps glTF metallic-roughness to the Lambert + Phong parameters above.
inline PhongMaterial phongFromMetallicRoughness(glm::dvec3 baseColour, double metallic,
                                                double roughness) {
  metallic = std::clamp(metallic, 0.0, 1.0);
  roughness = std::clamp(roughness, 0.0, 1.0);
  const double alpha = roughness * roughness;
  const double alpha2 = std::max(alpha * alpha, 1e-12);
  PhongMaterial m;
  m.albedo = baseColour * (1.0 - metallic);
  const glm::dvec3 f0 = glm::mix(glm::dvec3(kDielectricF0), baseColour, metallic);
  m.specular = f0 * (metallic + (1.0 - metallic) * (1.0 - roughness));
  m.exponent = std::clamp(0.125 / alpha2 - 0.5, 1.0, kMaxPhongExponent);
  return m;
}

// Maps KHR_materials_pbrSpecularGlossiness to the same parameters: albedo = diffuse ·
// (1 − max(specular)) (the extension's own split), ks = specular, and the exponent of
// roughness 1 − glossiness as above.
inline PhongMaterial phongFromSpecularGlossiness(glm::dvec3 diffuse, glm::dvec3 specular,
                                                 double glossiness) {
  specular = glm::clamp(specular, 0.0, 1.0);
  const double roughness = 1.0 - std::clamp(glossiness, 0.0, 1.0);
  const double alpha2 = std::max(std::pow(roughness, 4.0), 1e-12);
  PhongMaterial m;
  m.albedo = diffuse * (1.0 - std::max({specular.r, specular.g, specular.b}));
  m.specular = specular;
  m.exponent = std::clamp(0.125 / alpha2 - 0.5, 1.0, kMaxPhongExponent);
  return m;
}

// Whether phongFromMetallicRoughness gives a non-zero specular colour (for any non-black
// base colour): everything but a fully rough dielectric.
inline bool hasSpecularTerm(double metallic, double roughness) {
  return std::clamp(metallic, 0.0, 1.0) > 0.0 || std::clamp(roughness, 0.0, 1.0) < 1.0;
}

inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / std::max(e1 - e0, kMinConeWidth), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// window(d) above; range <= 0 or infinite means no range. Non-increasing in d and
// non-decreasing in range (the light trees' bounds rely on both); continuous, with a kink at
// d = range where its slope −4/range jumps to 0.
inline double rangeWindow(double distance, double range) {
  if (!(range > 0.0) || std::isinf(range)) return 1.0;
  const double r = distance / range;
  return std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
}

// The light-independent term: ambient · (a + ks) · occlusion.
inline glm::dvec3 ambientRadiance(const PhongMaterial& m, glm::dvec3 ambient, double occlusion) {
  return ambient * (m.albedo + m.specular) * occlusion;
}

// The bracket (a/π + ks·(n+2)/(2π)·max(R·V,0)^n) of the sum above: radiance per irradiance.
inline glm::dvec3 brdf(const PhongMaterial& m, glm::dvec3 n, glm::dvec3 l, glm::dvec3 v) {
  glm::dvec3 f = m.albedo / kPi;
  if (m.specular != glm::dvec3(0.0)) {
    const glm::dvec3 r = glm::reflect(-l, n);
    const double rv = std::max(glm::dot(r, v), 0.0);
    f += m.specular * ((m.exponent + 2.0) / (2.0 * kPi) * std::pow(rv, m.exponent));
  }
  return f;
}

// Rec. 709 luminance of linear RGB: how the map choice (render/rsm_choice.h) weighs a light's
// irradiance.
inline double luminance(glm::dvec3 rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// Irradiance at p (unit normal n) from `light`, and the unit vector l towards the light.
inline glm::dvec3 irradiance(const Light& light, glm::dvec3 p, glm::dvec3 n, glm::dvec3& l) {
  const glm::dvec3 radiant = glm::dvec3(light.colour) * double(light.intensity);
  if (light.type == LightType::Directional) {
    l = -glm::normalize(glm::dvec3(light.direction));
    return radiant * std::max(glm::dot(n, l), 0.0);
  }
  const glm::dvec3 toLight = glm::dvec3(light.position) - p;
  const double d2 = std::max(glm::dot(toLight, toLight), kMinDistanceSquared);
  const double d = std::sqrt(d2);
  l = toLight / d;
  double e = std::max(glm::dot(n, l), 0.0) / d2 * rangeWindow(d, light.range);
  if (light.type == LightType::Spot) {
    e *= smoothstep(std::cos(double(light.outerConeAngle)), std::cos(double(light.innerConeAngle)),
                    glm::dot(-l, glm::dvec3(light.direction)));
  }
  return radiant * e;
}

}  // namespace manylight::shading
