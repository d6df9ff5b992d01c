// `--indirect caches` (render/light_caches.h): per cache from uFirstCache on (one fragment of
// the cache target, cache c at texel (c mod width, c / width)), the light of one reflective
// shadow map's texels arriving at the cache's position, projected on glsl/sh_basis.glsl, added
// (blend ONE, ONE) to the coefficient targets. A texel of flux Φ and area A at y, normal n_t, sends towards the
// cache at q, along ω = (y − q)/d,
//   Φ · max(n_t·(−ω), 0) / (π · (d² + A/π))  per unit max(n·ω, 0),
// so a pixel's irradiance E(n) = Σ that · max(n·ω, 0), as glsl/indirect_exact.frag sums it;
// times farWeight(d, r), r the larger of the map's uNearRadius and kNearCells of the cache's
// cells: the pixels gather the rest themselves (render/near_field.h). A cluster of texels far
// enough from the cache counts as one texel (render/rsm_clusters.h). Beside the coefficients,
// the cache's correction for its normal n_c: the exact far irradiance there, Σ that ·
// max(n_c·ω, 0), less what the coefficients give n_c (linear in the light, so it adds up
// over maps and passes as they do).
uniform sampler2D uCachePosition;
uniform sampler2D uCacheNormal;  // the normal the cache's correction is exact for
uniform int uFirstCache;  // the caches before it kept their light from the frame before
uniform int uCacheCount;
uniform sampler2D uRsmPosition;
uniform sampler2D uRsmNormal;
uniform sampler2D uRsmFlux;
uniform int uRsmSize;
uniform int uFirstRow;
uniform int uRows;
uniform float uNearRadius;
// The map's clusters (render/rsm_clusters.h), kRsmClusterEdge² texels each:
uniform sampler2D uClusterCentre;  // xyz, radius (< 0: none reflects)
uniform sampler2D uClusterNormal;  // mean unit normal, 1 where its texels share its facing
uniform sampler2D uClusterFlux;    // Σ flux, mean texel area

out vec4 oSh0;
out vec4 oSh1;
out vec4 oSh2;
out vec4 oSh3;
out vec4 oSh4;
out vec4 oSh5;
out vec4 oSh6;
out vec4 oCorrection;

// Adds to c the far light of a texel (flux.rgb, area flux.w) at y, of normal nt, arriving at
// q for a near radius r, projected on the basis.
void addTexel(vec4 flux, vec3 y, vec3 nt, vec3 q, float r, vec3 nc, inout vec3 c[9],
              inout vec3 exact) {
  vec3 w = y - q;
  float d2 = max(dot(w, w), kMinDistanceSquared);
  float invD = inversesqrt(d2);
  vec3 omega = w * invD;
  float s = max(-dot(nt, omega), 0.0) / (kPi * (d2 + flux.w / kPi)) * farWeight(d2 * invD, r);
  if (s == 0.0) return;
  float y9[9];
  shBasis(omega, y9);
  vec3 f = flux.rgb * s;
  exact += f * max(dot(nc, omega), 0.0);
  // Written out: llvmpipe counts an inner loop's iterations against the invocation's
  // 65,535 (render/rsm.h, drawRsmRowPasses).
  c[0] += f * y9[0];
  c[1] += f * y9[1];
  c[2] += f * y9[2];
  c[3] += f * y9[3];
#ifdef SH_L2
  c[4] += f * y9[4];
  c[5] += f * y9[5];
  c[6] += f * y9[6];
  c[7] += f * y9[7];
  c[8] += f * y9[8];
#endif
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  int width = textureSize(uCachePosition, 0).x;
  int cache = px.y * width + px.x;
  if (cache < uFirstCache || cache >= uCacheCount) discard;
  vec4 node = texelFetch(uCachePosition, px, 0);  // position, cell edge
  vec3 q = node.xyz;
  vec3 nc = texelFetch(uCacheNormal, px, 0).xyz;
  vec3 exact = vec3(0.0);
  float r = max(uNearRadius, kNearCells * node.w);
  vec3 c[9] = vec3[9](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0),
                      vec3(0.0), vec3(0.0), vec3(0.0));
  const int kEdge = kRsmClusterEdge;
  for (int by = uFirstRow / kEdge; by < (uFirstRow + uRows) / kEdge; ++by) {
    for (int bx = 0; bx < uRsmSize / kEdge; ++bx) {
      ivec2 b = ivec2(bx, by);
      vec4 centre = texelFetch(uClusterCentre, b, 0);
      if (centre.w < 0.0) continue;
      vec4 mean = texelFetch(uClusterNormal, b, 0);
      float d = length(centre.xyz - q);
      if (mean.w > 0.0 && d > max(kRsmClusterDistance * centre.w, 2.0 * r + centre.w)) {
        addTexel(texelFetch(uClusterFlux, b, 0), centre.xyz, mean.xyz, q, r, nc, c, exact);
        continue;
      }
      for (int j = 0; j < kEdge * kEdge; ++j) {
        ivec2 t = b * kEdge + ivec2(j % kEdge, j / kEdge);
        vec4 flux = texelFetch(uRsmFlux, t, 0);
        if (flux.w == 0.0) continue;
        addTexel(flux, texelFetch(uRsmPosition, t, 0).xyz, texelFetch(uRsmNormal, t, 0).xyz, q,
                 r, nc, c, exact);
      }
    }
  }
  // The coefficients' 27 floats, RGB after RGB, in seven texels (three for SH L1).
  oSh0 = vec4(c[0], c[1].r);
  oSh1 = vec4(c[1].gb, c[2].rg);
  oSh2 = vec4(c[2].b, c[3]);
  oSh3 = vec4(c[4], c[5].r);
  oSh4 = vec4(c[5].gb, c[6].rg);
  oSh5 = vec4(c[6].b, c[7]);
  oSh6 = vec4(c[8], 0.0);
  oCorrection = vec4(exact - shIrradiance(c, nc), 0.0);
}
