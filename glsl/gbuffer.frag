// G-buffer pass: surface position, normal and the Lambert + Phong parameters of
// scene/shading_model.h, plus the light-independent radiance (ambient · albedo + emissive)
// written straight into the radiance target that the lighting passes add to.
in vec3 vWorld;
in vec3 vNormal;
in vec2 vTexcoord;
in vec4 vColour;

uniform vec4 uBaseColorFactor;
uniform float uMetallic;
uniform float uRoughness;
uniform vec3 uEmissive;
uniform bool uHasTexture;
uniform bool uDoubleSided;
uniform bool uMirrored;  // negative determinant: the winding, and so gl_FrontFacing, flips
uniform sampler2D uBaseColorTexture;  // linear RGBA (decoded from sRGB at upload)
uniform vec3 uAmbient;

out vec4 gPosition;  // xyz world position, w Phong exponent
out vec4 gNormal;    // xyz unit normal, w 1 where covered
out vec4 gAlbedo;    // rgb Lambert albedo
out vec4 gSpecular;  // rgb Phong specular colour
out vec4 gRadiance;  // rgb ambient · albedo + emissive, w coverage

const float kDielectricF0 = 0.04;
const float kMaxPhongExponent = 8192.0;

void main() {
  vec4 base = uBaseColorFactor * vColour;
  if (uHasTexture) base *= texture(uBaseColorTexture, vTexcoord);
  float metallic = clamp(uMetallic, 0.0, 1.0);
  float roughness = clamp(uRoughness, 0.0, 1.0);
  float alpha = roughness * roughness;
  float alpha2 = max(alpha * alpha, 1e-12);
  vec3 albedo = base.rgb * (1.0 - metallic);
  vec3 specular = mix(vec3(kDielectricF0), base.rgb, metallic) *
                  (metallic + (1.0 - metallic) * (1.0 - roughness));
  float exponent = clamp(2.0 / alpha2 - 2.0, 1.0, kMaxPhongExponent);

  vec3 n = normalize(vNormal);
  bool front = gl_FrontFacing != uMirrored;
  if (uDoubleSided && !front) n = -n;

  gPosition = vec4(vWorld, exponent);
  gNormal = vec4(n, 1.0);
  gAlbedo = vec4(albedo, 0.0);
  gSpecular = vec4(specular, 0.0);
  gRadiance = vec4(uAmbient * albedo + uEmissive, 1.0);
}
