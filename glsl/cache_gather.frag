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
// the exact far irradiance for the cache's normal n_c, Σ that · max(n_c·ω, 0) (linear in the
// light, so it adds up over maps and passes as the coefficients do).
uniform sampler2D uCachePosition;
uniform sampler2D uCacheNormal;  // n_c, the normal of the cache's exact irradiance
uniform int uFirstCache;  // the caches before it kept their light from the frame before
uniform int uCacheCount;
uniform int uRsmSize;
uniform int uFirstRow;
uniform int uRows;
uniform float uNearRadius;
// The map's clusters (render/rsm_clusters.h), kRsmClusterEdge² texels each, and their texels
// (render/rsm.h, RsmClusterTextures):
uniform sampler2D uClusterCentre;  // xyz, radius (< 0: none reflects); a texel's position
uniform sampler2D uClusterNormal;  // mean unit normal, 1 where its texels share its facing
uniform sampler2D uClusterFlux;    // Σ flux, mean texel area; a texel's flux and area

out vec4 oSh0;
out vec4 oSh1;
out vec4 oSh2;
out vec4 oSh3;
out vec4 oSh4;
out vec4 oSh5;
out vec4 oSh6;
out vec4 oExact;

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
  // One loop over the clusters of the pass's rows, and the texels of a cluster being summed
  // texel by texel, one record an iteration: llvmpipe runs an inner loop for every lane
  // whenever one lane takes it, and neighbouring caches sum different clusters.
  const int kSlots = kRsmClusterEdge * kRsmClusterEdge;
  int side = uRsmSize / kRsmClusterEdge;  // clusters a side (render/rsm.h's layout)
  int clusterRows = (side + kSlots - 1) / kSlots;
  ivec2 b = ivec2(0, uFirstRow / kRsmClusterEdge);
  int lastRow = (uFirstRow + uRows) / kRsmClusterEdge;
  int texel = -1;  // of the cluster being summed, or −1
  while (b.y < lastRow) {
    ivec2 at = texel < 0 ? ivec2(side * (b.y % kSlots) + b.x, b.y / kSlots)
                         : ivec2(kSlots * b.x + texel, clusterRows + b.y);
    vec4 centre = texelFetch(uClusterCentre, at, 0);
    vec4 mean = texelFetch(uClusterNormal, at, 0);
    vec4 flux = texelFetch(uClusterFlux, at, 0);
    float d = length(centre.xyz - q);
    // A cluster that reflects, not wholly within r (where the far weight is 0), and too near
    // to count as one texel or not flat: summed texel by texel.
    bool expand = texel < 0 && centre.w >= 0.0 && d + centre.w > r &&
                  !(mean.w > 0.0 && d > max(kRsmClusterDistance * centre.w, 2.0 * r + centre.w));
    bool whole = texel < 0 && centre.w >= 0.0 && !expand;
    if (whole || (texel >= 0 && flux.w != 0.0))
      addTexel(flux, centre.xyz, mean.xyz, q, r, nc, c, exact);
    if (expand) {
      texel = 0;
    } else if (texel >= 0 && texel + 1 < kSlots) {
      ++texel;
    } else {
      texel = -1;
      if (++b.x == side) b = ivec2(0, b.y + 1);
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
  oExact = vec4(exact, 0.0);
}
