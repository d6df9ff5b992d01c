// `--indirect caches` (render/light_caches.h): each pixel's irradiance interpolated from the
// caches at the eight nodes of its cell in its cascade of the Cache Address Volume, each
// cache's spherical harmonics (glsl/sh_basis.glsl) evaluated for the pixel's normal; in the
// transition band (glsl/cache_cascade.glsl), blended with the next cascade's linearly across
// the band. Added (blend ONE, ONE) to the radiance target: albedo/π · E.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler3D uCav;  // per cascade (R + 1)³ nodes stacked in z: a cache index, or −1
uniform sampler2D uSh0;
uniform sampler2D uSh1;
uniform sampler2D uSh2;
uniform sampler2D uSh3;
uniform sampler2D uSh4;
uniform sampler2D uSh5;
uniform sampler2D uSh6;
uniform int uResolution;  // R: cells per axis of a cascade
uniform vec3 uOrigin[8];  // per cascade, its node (0, 0, 0)

out vec4 oRadiance;

// The cache's irradiance for unit normal n.
vec3 cacheIrradiance(int cache, vec3 n) {
  int width = textureSize(uSh0, 0).x;
  ivec2 t = ivec2(cache % width, cache / width);
  vec4 a = texelFetch(uSh0, t, 0), b = texelFetch(uSh1, t, 0), c = texelFetch(uSh2, t, 0);
  float y[9];
  shBasis(n, y);
  vec3 e = shCosine(0) * y[0] * a.rgb + shCosine(1) * y[1] * vec3(a.a, b.rg) +
           shCosine(2) * y[2] * vec3(b.ba, c.r) + shCosine(3) * y[3] * c.gba;
#ifdef SH_L2
  vec4 d = texelFetch(uSh3, t, 0), f = texelFetch(uSh4, t, 0), g = texelFetch(uSh5, t, 0);
  vec4 h = texelFetch(uSh6, t, 0);
  e += shCosine(4) * (y[4] * d.rgb + y[5] * vec3(d.a, f.rg) + y[6] * vec3(f.ba, g.r) +
                      y[7] * g.gba + y[8] * h.rgb);
#endif
  return max(e, vec3(0.0));
}

// Trilinear over the caches present at the eight nodes around p in cascade k, those behind
// the pixel's surface (below its tangent plane) left out where any lies in front: a cache
// behind a wall sees the light in front of the wall's other side, and without visibility
// it would leak through.
vec3 cascadeIrradiance(int k, vec3 p, vec3 n) {
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
    vec3 e = cacheIrradiance(int(cache), n);
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
  vec3 e = cascadeIrradiance(k, p, normal.xyz);
  if (band > 0.0) e = mix(e, cascadeIrradiance(k + 1, p, normal.xyz), band);
  oRadiance = vec4(texelFetch(uAlbedo, px, 0).rgb / kPi * e, 0.0);
}
