// `--indirect caches` (render/light_caches.h): each pixel's irradiance interpolated from the
// caches at the eight nodes of its cell in its cascade of the Cache Address Volume, each
// cache's spherical harmonics (glsl/sh_basis.glsl) evaluated for the pixel's normal; in the
// transition band (glsl/cache_cascade.glsl), blended with the next cascade's linearly across
// the band. Added (blend ONE, ONE) to the radiance target: albedo/π · E.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler3D uCav;  // per cascade (R + 1)³ nodes stacked in z: its first cache, or −1
uniform sampler2D uSh0;
uniform sampler2D uSh1;
uniform sampler2D uSh2;
uniform sampler2D uSh3;
uniform sampler2D uSh4;
uniform sampler2D uSh5;
uniform sampler2D uSh6;
uniform sampler2D uCorrection;   // per cache: exact less SH irradiance for its normal
uniform sampler2D uCacheNext;    // per cache: the next cache of its node (or −1), its bin
uniform int uResolution;  // R: cells per axis of a cascade
uniform vec3 uOrigin[8];  // per cascade, its node (0, 0, 0)

out vec4 oRadiance;

// render/light_caches.h's normalBin.
int normalBin(vec3 n) {
  vec3 m = abs(n);
  int axis = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  float major = max(m[axis], 1e-20);
  int face = 2 * axis + (n[axis] < 0.0 ? 1 : 0);
  float u = n[(axis + 1) % 3] / major, v = n[(axis + 2) % 3] / major;
  float halfGrid = 0.5 * float(kNormalBinGrid);
  int cu = clamp(int(floor((u + 1.0) * halfGrid)), 0, kNormalBinGrid - 1);
  int cv = clamp(int(floor((v + 1.0) * halfGrid)), 0, kNormalBinGrid - 1);
  return (face * kNormalBinGrid + cv) * kNormalBinGrid + cu;
}

// render/light_caches.h's binNormal.
vec3 binNormal(int bin) {
  int g = kNormalBinGrid;
  int face = bin / (g * g), axis = face / 2;
  vec3 d = vec3(0.0);
  d[axis] = face % 2 == 0 ? 1.0 : -1.0;
  d[(axis + 1) % 3] = (2.0 * float(bin % g) + 1.0) / float(g) - 1.0;
  d[(axis + 2) % 3] = (2.0 * float(bin / g % g) + 1.0) / float(g) - 1.0;
  return normalize(d);
}

// The irradiance for unit normal n (of bin `bin`, `towards` the cosine to its centre) from the
// caches of the node whose first is `first`: the coefficients', plus the correction of the
// node's cache of that bin where n is within kCorrectionCosine of the centre (all of it
// there).
vec3 cacheIrradiance(int first, vec3 n, int bin, float towards) {
  // Only a normal within kCorrectionCosine of its bin's centre has that bin's cache at every
  // node around it (LightCaches' allocation); the others read the first.
  int cache = towards > kCorrectionCosine ? first : -1;
  for (int j = 0; j < 6 * kNormalBinGrid * kNormalBinGrid && cache >= 0; ++j) {
    vec2 link = texelFetch(uCacheNext, cacheTexel(cache), 0).rg;
    if (int(link.y) == bin) break;
    cache = int(link.x);
  }
  bool corrected = cache >= 0;
  if (!corrected) cache = first;
  ivec2 t = cacheTexel(cache);
  vec4 a = texelFetch(uSh0, t, 0), b = texelFetch(uSh1, t, 0), c = texelFetch(uSh2, t, 0);
  vec3 coefficients[9] = vec3[9](a.rgb, vec3(a.a, b.rg), vec3(b.ba, c.r), c.gba, vec3(0.0),
                                 vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
#ifdef SH_L2
  vec4 d = texelFetch(uSh3, t, 0), f = texelFetch(uSh4, t, 0), g = texelFetch(uSh5, t, 0);
  vec4 h = texelFetch(uSh6, t, 0);
  coefficients[4] = d.rgb;
  coefficients[5] = vec3(d.a, f.rg);
  coefficients[6] = vec3(f.ba, g.r);
  coefficients[7] = g.gba;
  coefficients[8] = h.rgb;
#endif
  vec3 e = shIrradiance(coefficients, n);
  if (corrected)
    e += smoothstep(kCorrectionCosine, 1.0, towards) * texelFetch(uCorrection, t, 0).rgb;
  return max(e, vec3(0.0));
}

// Trilinear over the caches present at the eight nodes around p in cascade k, those behind
// the pixel's surface (below its tangent plane) left out where any lies in front: a cache
// behind a wall sees the light in front of the wall's other side, and without visibility
// it would leak through.
vec3 cascadeIrradiance(int k, vec3 p, vec3 n, int bin, float towards) {
  vec3 g = (p - uOrigin[k]) / uCell[k];
  ivec3 base = ivec3(floor(g));
  vec3 f = g - vec3(base);
  vec3 sum = vec3(0.0), behind = vec3(0.0);
  float weights = 0.0, behindWeights = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    ivec3 node = clamp(base + o, ivec3(0), ivec3(uResolution));
    float cache = texelFetch(uCav, ivec3(node.xy, node.z + k * (uResolution + 1)), 0).r;
    if (cache < 0.0) continue;
    vec3 t = mix(1.0 - f, f, vec3(o));
    float w = t.x * t.y * t.z;
    vec3 e = cacheIrradiance(int(cache), n, bin, towards);
    if (dot(uOrigin[k] + vec3(node) * uCell[k] - p, n) >= 0.0) {
      sum += w * e;
      weights += w;
    } else {
      behind += w * e;
      behindWeights += w;
    }
  }
  if (weights > 0.0) return sum / weights;
  return behindWeights > 0.0 ? behind / behindWeights : vec3(0.0);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) discard;
  vec3 p = texelFetch(uPosition, px, 0).xyz;
  float band;
  int k = cacheCascade(p, band);
  if (k == uCascades) discard;  // beyond the largest cascade: no caches
  int bin = normalBin(normal.xyz);
  float towards = dot(normal.xyz, binNormal(bin));
  vec3 e = cascadeIrradiance(k, p, normal.xyz, bin, towards);
  if (band > 0.0) e = mix(e, cascadeIrradiance(k + 1, p, normal.xyz, bin, towards), band);
  oRadiance = vec4(texelFetch(uAlbedo, px, 0).rgb / kPi * e, 0.0);
}
