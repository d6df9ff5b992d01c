// `--indirect caches` (render/light_caches.h): each pixel's irradiance interpolated from the
// caches at the eight nodes of its cell in its cascade of the Cache Address Volume, each
// cache's spherical harmonics (glsl/sh_basis.glsl) evaluated for the pixel's normal, corrected
// towards the cache's exact irradiance for its bin's centre; with CENTRED_NORMALS, for the
// pixels whose normal is that centre, the exact irradiance alone. In the transition band
// (glsl/cache_cascade.glsl) the next cascade's is blended in linearly across the band: this
// pass adds (1 − band) of the pixel's cascade's, with NEXT_CASCADE band of the next one's.
// The stencil (render/pixel_classes.h) picks each pass's pixels. Added (blend ONE, ONE) to
// the radiance target: albedo/π · E.
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
uniform sampler2D uExact;        // per cache: its far irradiance, exact, for its normal
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

// The weights (shIrradianceWeights) of a pixel's normal n and of its bin's centre, and how much
// of the correction towards the exact irradiance at the centre it takes: all of it at the
// centre, none from kCorrectionCosine away.
struct Normal {
  vec3 n;
  int bin;
  float towards;  // n · the bin's centre
  float correction;
  float wn[9], wc[9];
};

// The node's cache of bin `bin`, in the list from `first`; −1 where it has none.
int binCache(int first, int bin) {
  int cache = first;
  for (int j = 0; j < 6 * kNormalBinGrid * kNormalBinGrid && cache >= 0; ++j) {
    vec2 link = texelFetch(uCacheNext, cacheTexel(cache), 0).rg;
    if (int(link.y) == bin) break;
    cache = int(link.x);
  }
  return cache;
}

#ifdef CENTRED_NORMALS
// A normal at its bin's centre (kCentredCosine, render/light_caches.h; a flat wall along an
// axis): the exact irradiance of the node's cache of that bin, and 1. Every node of the
// pixel's cell has one: allocateCaches marks a pixel centred only then (a node without it,
// should one be read, is left out: 0).
vec4 cacheIrradiance(int first, Normal p) {
  int cache = binCache(first, p.bin);
  return cache >= 0 ? vec4(texelFetch(uExact, cacheTexel(cache), 0).rgb, 1.0) : vec4(0.0);
}
#else
// The irradiance for the pixel's normal from the caches of the node whose first is `first`,
// and 1: the coefficients', and where n is within kCorrectionCosine of its bin's centre, the
// correction of the node's cache of that bin, SH(n) + t (exact − SH(centre)).
vec4 cacheIrradiance(int first, Normal p) {
  // Only a normal within kCorrectionCosine of its bin's centre has that bin's cache at every
  // node around it (LightCaches' allocation); the others read the first.
  int cache = p.towards > kCorrectionCosine ? binCache(first, p.bin) : -1;
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
  vec3 e = shApply(coefficients, p.wn);
  if (corrected)
    e += p.correction * (texelFetch(uExact, t, 0).rgb - shApply(coefficients, p.wc));
  return vec4(max(e, vec3(0.0)), 1.0);
}
#endif

// Trilinear over the caches present at the eight nodes around p in cascade k, those behind
// the pixel's surface (below its tangent plane) left out where any lies in front: a cache
// behind a wall sees the light in front of the wall's other side, and without visibility
// it would leak through.
vec3 cascadeIrradiance(int k, vec3 p, Normal normal) {
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
    vec4 e = cacheIrradiance(int(cache), normal);
    float w = t.x * t.y * t.z * e.w;
    if (dot(uOrigin[k] + vec3(node) * uCell[k] - p, normal.n) >= 0.0) {
      sum += w * e.rgb;
      weights += w;
    } else {
      behind += w * e.rgb;
      behindWeights += w;
    }
  }
  if (weights > 0.0) return sum / weights;
  return behindWeights > 0.0 ? behind / behindWeights : vec3(0.0);
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 p = texelFetch(uPosition, px, 0).xyz;
  float band;
  int k = cacheCascade(p, band);
#ifdef NEXT_CASCADE
  // A pixel of a transition band (render/pixel_classes.h): the next cascade's share.
  ++k;
  float share = band;
#else
  float share = 1.0 - band;
#endif
  // Beyond the largest cascade, where the CPU's classes and this differ by a rounding: no
  // caches (a share of 0, not a discard: see glsl/cache_near.frag).
  if (k >= uCascades) share = 0.0;
  k = min(k, uCascades - 1);
  Normal n;
  n.n = texelFetch(uNormal, px, 0).xyz;
  n.bin = normalBin(n.n);
#ifndef CENTRED_NORMALS
  vec3 centre = binNormal(n.bin);
  n.towards = dot(n.n, centre);
  n.correction = smoothstep(kCorrectionCosine, 1.0, n.towards);
  shIrradianceWeights(n.n, n.wn);
  shIrradianceWeights(centre, n.wc);
#endif
  vec3 e = share * cascadeIrradiance(k, p, n);
  oRadiance = vec4(texelFetch(uAlbedo, px, 0).rgb / kPi * e, 0.0);
}
