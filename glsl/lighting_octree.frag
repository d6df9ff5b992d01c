// The octree method: at each pixel, every light of the global list (lights that reach
// everywhere) and of the pixel's octree leaf, evaluated exactly, added (blend ONE, ONE) to
// the radiance target. The two lists read as one: entries [0, uGlobalCount) are the global
// list's, the rest the leaf's. A pass evaluates entries [uFirstEntry, uFirstEntry +
// uEntriesPerPass), uEntriesPerPass ≤ kOctreeEntriesPerPass; longer lists continue in
// further passes, so no list is capped.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uSpecular;
uniform vec3 uEye;
uniform vec3 uForward;
uniform bool uOrthographic;
uniform int uGlobalCount;
uniform int uFirstEntry;
uniform int uEntriesPerPass;

out vec4 oRadiance;

// Irradiance at s from the light in slot `slot` of the light texture, of any type, and the
// unit vector l towards it. A ranged light out of range adds exactly 0 (its window is 0), so
// it is skipped with one texel read.
vec3 slotIrradiance(int slot, Surface s, out vec3 l) {
  vec4 a = texelFetch(uLights, kTexelsPerLight * slot);
  if (a.w < 0.0) {  // directional
    l = a.xyz;
    return texelFetch(uLights, kTexelsPerLight * slot + 2).rgb * max(dot(s.normal, l), 0.0);
  }
  vec3 toLight = a.xyz - s.position;
  l = vec3(0.0, 0.0, 1.0);
  if (dot(toLight, toLight) * a.w >= 1.0) return vec3(0.0);
  return spotTexelsIrradiance(a, texelFetch(uLights, kTexelsPerLight * slot + 1),
                              texelFetch(uLights, kTexelsPerLight * slot + 2), s.position,
                              s.normal, l);
}

// The light of list entry j: the global list's below uGlobalCount, else the leaf's.
int entrySlot(int j, uvec2 leaf) {
  int at = j < uGlobalCount ? j : int(leaf.x) + (j - uGlobalCount);
  return int(texelFetch(uOctreeIndices, at).r);
}

vec3 entryIrradiance(int j, uvec2 leaf, Surface s) {
  vec3 l;
  return slotIrradiance(entrySlot(j, leaf), s, l);
}
vec3 entryRadiance(int j, uvec2 leaf, Surface s) {
  vec3 l;
  vec3 e = slotIrradiance(entrySlot(j, leaf), s, l);
  return brdf(s, l) * e;
}
#define IRRADIANCE(k) entryIrradiance(k, leaf, s)
#define RADIANCE(k) entryRadiance(k, leaf, s)
// sum += TERM(j) for j in [uFirstEntry, end). (One line: GLSL 3.30 has no line continuation.)
#define SUM_ENTRIES(TERM) for (j = uFirstEntry; j + 4 <= end; j += 4) { sum += (TERM(j) + TERM(j + 1)) + (TERM(j + 2) + TERM(j + 3)); } for (; j < end; ++j) sum += TERM(j)

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) discard;  // background
  vec4 position = texelFetch(uPosition, px, 0);
  uvec2 leaf = octreeList(position.xyz);
  int end = min(uGlobalCount + int(leaf.y), uFirstEntry + uEntriesPerPass);
  if (end <= uFirstEntry) discard;  // this pixel's list ended in an earlier pass
  Surface s;
  s.position = position.xyz;
  s.normal = normal.xyz;
  s.view = uOrthographic ? -uForward : normalize(uEye - position.xyz);
  s.albedo = texelFetch(uAlbedo, px, 0).rgb;
  s.specular = texelFetch(uSpecular, px, 0).rgb;
  s.exponent = position.w;
  vec3 sum = vec3(0.0);
  int j;
  // Unrolled by four, as the reference's loops are: fewer iterations of a loop whose bounds
  // llvmpipe cannot see, and sums of four before they meet the running sum.
#ifdef HAS_SPECULAR
  if (s.specular != vec3(0.0)) {
    SUM_ENTRIES(RADIANCE);
    oRadiance = vec4(sum, 0.0);
    return;
  }
#endif
  // Pure Lambert: the BRDF is constant, so sum irradiance only.
  SUM_ENTRIES(IRRADIANCE);
  oRadiance = vec4(sum * (s.albedo / kPi), 0.0);
}
