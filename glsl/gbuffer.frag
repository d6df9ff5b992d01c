// G-buffer pass: surface position, normal and the Lambert + Phong parameters of
// scene/shading_model.h from the material's factors and textures, plus the light-independent
// radiance (ambient · (albedo + specular) · occlusion + emissive) written straight into the
// radiance target that the lighting passes add to. Unlit surfaces (KHR_materials_unlit, and
// points and lines without normals) write their base colour there and mark the normal target
// uncovered, so no lighting pass touches them. The AOV variants (render/aov.h: "AOV" and one
// AOV_ channel) write that material channel into the radiance target instead, and the
// renderer runs no lighting pass after them.
in vec3 vWorld;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vTexcoord0;
in vec2 vTexcoord1;
in vec4 vColour;

// One texture of the material (scene/scene.h TextureRef): whether it is bound, which UV set
// it reads, and its KHR_texture_transform.
struct TextureSlot {
  bool bound;
  bool secondSet;
  mat3 transform;
};
uniform TextureSlot uBaseColourSlot, uMetalRoughSlot, uNormalSlot, uOcclusionSlot, uEmissiveSlot;
// Linear values: colour textures are decoded from sRGB at upload, data textures are not.
uniform sampler2D uBaseColourTexture, uMetalRoughTexture, uNormalTexture, uOcclusionTexture,
    uEmissiveTexture;

uniform vec4 uBaseColorFactor;
uniform float uMetallic;
uniform float uRoughness;
uniform vec3 uEmissive;
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform float uAlphaCutoff;  // < 0: no cutoff (alpha modes other than MASK)
uniform bool uUnlit;
uniform bool uSpecularGlossiness;  // KHR_materials_pbrSpecularGlossiness (scene/scene.h)
uniform vec3 uSpecularFactor;
uniform float uGlossiness;
uniform bool uOpaque;  // alpha mode OPAQUE, where glTF ignores alpha
uniform bool uDoubleSided;
uniform bool uMirrored;  // negative determinant: the winding, and so gl_FrontFacing, flips
uniform vec3 uAmbient;

out vec4 gPosition;  // xyz world position, w Phong exponent
out vec4 gNormal;    // xyz unit normal, w 1 where lit
out vec4 gAlbedo;    // rgb Lambert albedo, w alpha (what render/blend_pass.cpp composites by)
out vec4 gSpecular;  // rgb Phong specular colour
out vec4 gRadiance;  // rgb ambient · (albedo + specular) · occlusion + emissive, w coverage

vec4 sampleSlot(TextureSlot slot, sampler2D tex) {
  vec2 uv = slot.secondSet ? vTexcoord1 : vTexcoord0;
  return texture(tex, (slot.transform * vec3(uv, 1.0)).xy);
}

// The shading normal: the interpolated one, perturbed by the normal texture in the tangent
// frame (bitangent cross(n, t) · w), flipped on the back of a double-sided surface.
vec3 shadingNormal(bool front) {
  vec3 n = normalize(vNormal);
  if (uNormalSlot.bound && dot(vTangent.xyz, vTangent.xyz) > 0.0) {
    vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
    vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
    vec3 m = sampleSlot(uNormalSlot, uNormalTexture).xyz * 2.0 - 1.0;
    m.xy *= uNormalScale;
    vec3 perturbed = mat3(t, b, n) * m;
    if (dot(perturbed, perturbed) > 0.0) n = normalize(perturbed);
  }
  return uDoubleSided && !front ? -n : n;
}

// Metallic and perceptual roughness, factors times the texture's B and G, clamped to [0, 1]
// (specular-glossiness: metallic 0, roughness 1 − glossiness).
vec2 metallicRoughness() {
  if (uSpecularGlossiness) {
    float gloss = uGlossiness;
    if (uMetalRoughSlot.bound) gloss *= sampleSlot(uMetalRoughSlot, uMetalRoughTexture).a;
    return vec2(0.0, 1.0 - clamp(gloss, 0.0, 1.0));
  }
  vec2 mr = vec2(uMetallic, uRoughness);
  if (uMetalRoughSlot.bound) mr *= sampleSlot(uMetalRoughSlot, uMetalRoughTexture).bg;
  return clamp(mr, 0.0, 1.0);
}

// The occlusion texture's R (1 without one), before the strength.
float occlusionTexel() {
  return uOcclusionSlot.bound ? sampleSlot(uOcclusionSlot, uOcclusionTexture).r : 1.0;
}

// Emissive factor × strength × texture.
vec3 emissiveRadiance() {
  vec3 emissive = uEmissive;
  if (uEmissiveSlot.bound) emissive *= sampleSlot(uEmissiveSlot, uEmissiveTexture).rgb;
  return emissive;
}

#ifdef AOV
// The chosen channel, in the values of render/aov.h (normals as (n + 1) / 2), with coverage 1;
// on unlit surfaces, whose shading reads only base colour and alpha, the other channels are
// uncovered (0, 0, 0, 0).
vec4 aovValue(vec4 base) {
#if defined(AOV_BASE_COLOUR)
  return vec4(base.rgb, 1.0);
#elif defined(AOV_ALPHA)
  return vec4(vec3(uOpaque ? 1.0 : base.a), 1.0);
#else
  if (uUnlit) return vec4(0.0);
#if defined(AOV_METALLIC)
  return vec4(vec3(metallicRoughness().x), 1.0);
#elif defined(AOV_ROUGHNESS)
  return vec4(vec3(metallicRoughness().y), 1.0);
#elif defined(AOV_NORMAL)
  return vec4(shadingNormal(gl_FrontFacing != uMirrored) * 0.5 + 0.5, 1.0);
#elif defined(AOV_EMISSIVE)
  return vec4(emissiveRadiance(), 1.0);
#elif defined(AOV_OCCLUSION)
  return vec4(vec3(occlusionTexel()), 1.0);
#else
#error "AOV needs one AOV_ channel"
#endif
#endif
}
#endif

void main() {
  vec4 base = uBaseColorFactor * vColour;
  if (uBaseColourSlot.bound) base *= sampleSlot(uBaseColourSlot, uBaseColourTexture);
  if (base.a < uAlphaCutoff) discard;
#ifdef AOV
  gPosition = vec4(vWorld, 1.0);
  gNormal = vec4(0.0);
  gAlbedo = vec4(0.0);
  gSpecular = vec4(0.0);
  gRadiance = aovValue(base);
#else
  if (uUnlit) {
    gPosition = vec4(vWorld, 1.0);
    gNormal = vec4(0.0);
    gAlbedo = vec4(0.0, 0.0, 0.0, base.a);
    gSpecular = vec4(0.0);
    gRadiance = vec4(base.rgb, 1.0);
    return;
  }
  float roughness;
  vec3 albedo, specular;
  if (uSpecularGlossiness) {
    vec4 sg = vec4(uSpecularFactor, uGlossiness);
    if (uMetalRoughSlot.bound) sg *= sampleSlot(uMetalRoughSlot, uMetalRoughTexture);
    specular = clamp(sg.rgb, 0.0, 1.0);
    roughness = 1.0 - clamp(sg.a, 0.0, 1.0);
    albedo = base.rgb * (1.0 - max(specular.r, max(specular.g, specular.b)));
  } else {
    vec2 mr = metallicRoughness();
    float metallic = mr.x;
    roughness = mr.y;
    albedo = base.rgb * (1.0 - metallic);
    specular = mix(vec3(kDielectricF0), base.rgb, metallic) *
               (metallic + (1.0 - metallic) * (1.0 - roughness));
  }
  float alpha = roughness * roughness;
  float alpha2 = max(alpha * alpha, 1e-12);
  float exponent = clamp(0.125 / alpha2 - 0.5, 1.0, kMaxPhongExponent);
  float occlusion = 1.0 + uOcclusionStrength * (occlusionTexel() - 1.0);
  vec3 emissive = emissiveRadiance();

  bool front = gl_FrontFacing != uMirrored;
  gPosition = vec4(vWorld, exponent);
  gNormal = vec4(shadingNormal(front), 1.0);
  gAlbedo = vec4(albedo, base.a);
  gSpecular = vec4(specular, 0.0);
  gRadiance = vec4(uAmbient * (albedo + specular) * occlusion + emissive, 1.0);
#endif
}
