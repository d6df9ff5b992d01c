// G-buffer pass: surface position, normal and the Lambert + Phong parameters of
// scene/shading_model.h from the material's factors and textures, plus the light-independent
// radiance (ambient · (albedo + specular) · occlusion + emissive) written straight into the
// radiance target that the lighting passes add to. Unlit surfaces (KHR_materials_unlit, and
// points and lines without normals) write their base colour there and mark the normal target
// uncovered, so no lighting pass touches them.
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
uniform bool uDoubleSided;
uniform bool uMirrored;  // negative determinant: the winding, and so gl_FrontFacing, flips
uniform vec3 uAmbient;

out vec4 gPosition;  // xyz world position, w Phong exponent
out vec4 gNormal;    // xyz unit normal, w 1 where lit
out vec4 gAlbedo;    // rgb Lambert albedo, w alpha (what render/blend_pass.cpp composites by)
out vec4 gSpecular;  // rgb Phong specular colour
out vec4 gRadiance;  // rgb ambient · (albedo + specular) · occlusion + emissive, w coverage

const float kDielectricF0 = 0.04;
const float kMaxPhongExponent = 8192.0;

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

void main() {
  vec4 base = uBaseColorFactor * vColour;
  if (uBaseColourSlot.bound) base *= sampleSlot(uBaseColourSlot, uBaseColourTexture);
  if (base.a < uAlphaCutoff) discard;
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
    float metallic = uMetallic;
    roughness = uRoughness;
    if (uMetalRoughSlot.bound) {
      vec4 mr = sampleSlot(uMetalRoughSlot, uMetalRoughTexture);
      metallic *= mr.b;
      roughness *= mr.g;
    }
    metallic = clamp(metallic, 0.0, 1.0);
    roughness = clamp(roughness, 0.0, 1.0);
    albedo = base.rgb * (1.0 - metallic);
    specular = mix(vec3(kDielectricF0), base.rgb, metallic) *
               (metallic + (1.0 - metallic) * (1.0 - roughness));
  }
  float alpha = roughness * roughness;
  float alpha2 = max(alpha * alpha, 1e-12);
  float exponent = clamp(0.125 / alpha2 - 0.5, 1.0, kMaxPhongExponent);
  float occlusion = 1.0;
  if (uOcclusionSlot.bound) {
    occlusion = 1.0 + uOcclusionStrength * (sampleSlot(uOcclusionSlot, uOcclusionTexture).r - 1.0);
  }
  vec3 emissive = uEmissive;
  if (uEmissiveSlot.bound) emissive *= sampleSlot(uEmissiveSlot, uEmissiveTexture).rgb;

  bool front = gl_FrontFacing != uMirrored;
  gPosition = vec4(vWorld, exponent);
  gNormal = vec4(shadingNormal(front), 1.0);
  gAlbedo = vec4(albedo, base.a);
  gSpecular = vec4(specular, 0.0);
  gRadiance = vec4(uAmbient * (albedo + specular) * occlusion + emissive, 1.0);
}
