// `--indirect caches`, the near field (render/near_field.h): every map texel within twice its
// near radius r of the pixel lights it as glsl/indirect_exact.frag's kernel times
// 1 − farWeight (the caches carry the rest), added (blend ONE, ONE) to the radiance target.
// r is the larger of the texel's map radius and kNearCells cells of the pixel's cascade; in a
// transition band the near light of both cascades is blended as the caches are. The texels
// are found in the cascade's grid, the cells within 2r of the pixel, and of those only the
// [uFirst, uFirst + uCount) th in the cells' order are read: one pass stays under
// llvmpipe's 65,535 loop iterations.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
// Per cascade, every texel ordered by the cascade's grid cell:
uniform sampler2D uTexelPosition;  // xyz, the map's near radius
uniform sampler2D uTexelNormal;    // xyz, patch area
uniform sampler2D uTexelFlux;      // rgb
uniform sampler3D uGrid;           // per cascade's cell (stacked in z): its first texel, count
uniform sampler3D uPlanes;         // per cell: the plane its texels share (n, n·p), or 0
uniform vec3 uGridOrigin;
uniform float uGridCell[8];
uniform float uGridReach[8];  // per cascade, twice the largest near radius: no texel reaches further
uniform ivec3 uGridCells[8];
uniform int uGridFirstZ[8];
uniform int uFirst;
uniform int uCount;

out vec4 oRadiance;

vec3 texelLight(int i, vec3 x, vec3 n, float cascadeRadius) {
  int width = textureSize(uTexelPosition, 0).x;
  ivec2 t = ivec2(i % width, i / width);
  vec4 pr = texelFetch(uTexelPosition, t, 0);
  float r = max(pr.w, cascadeRadius);
  vec3 w = pr.xyz - x;
  float d2 = max(dot(w, w), kMinDistanceSquared);
  if (d2 >= 4.0 * r * r) return vec3(0.0);
  vec4 na = texelFetch(uTexelNormal, t, 0);
  float c = max(dot(n, w), 0.0) * max(-dot(na.xyz, w), 0.0);
  float near = 1.0 - farWeight(sqrt(d2), r);
  return texelFetch(uTexelFlux, t, 0).rgb * (near * c / (d2 * (d2 + na.w / kPi)));
}

// Σ over the near texels of cascade k's grid: the irradiance times π.
vec3 nearLight(int k, vec3 x, vec3 n) {
  float cascadeRadius = kNearCells * uCell[k];
  ivec3 lo = max(ivec3(floor((x - uGridReach[k] - uGridOrigin) / uGridCell[k])), ivec3(0));
  ivec3 hi = min(ivec3(floor((x + uGridReach[k] - uGridOrigin) / uGridCell[k])), uGridCells[k] - 1);
  int seen = 0;  // texels of the cells before this one
  float tolerance = kPlaneTolerance * uGridCell[k];
  float reach = uGridReach[k];
  vec3 sum = vec3(0.0);
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        ivec3 cell = ivec3(cx, y, z + uGridFirstZ[k]);
        vec2 range = texelFetch(uGrid, cell, 0).rg;
        int count = int(range.y);
        vec3 boxLo = uGridOrigin + vec3(cx, y, z) * uGridCell[k];
        vec3 outside = max(max(boxLo - x, x - boxLo - uGridCell[k]), 0.0);
        vec3 centre = boxLo + 0.5 * uGridCell[k] - x;
        if (count == 0 || dot(outside, outside) >= reach * reach ||
            dot(n, centre) + 0.5 * uGridCell[k] * dot(abs(n), vec3(1.0)) <= 0.0) {
          // Empty, beyond every texel's reach, or wholly behind x's surface: no light from it.
          count = 0;
        } else {
          // In or behind the plane of all the cell's texels, x gets no light from them: each
          // sends its light to the side its normal faces.
          vec4 plane = texelFetch(uPlanes, cell, 0);
          if (plane.xyz != vec3(0.0) && dot(plane.xyz, x) - plane.w <= tolerance) count = 0;
        }
        int first = max(uFirst - seen, 0), last = min(uFirst + uCount - seen, count);
        for (int j = first; j < last; ++j) {
          sum += texelLight(int(range.x) + j, x, n, cascadeRadius);
        }
        seen += int(range.y);
      }
    }
  }
  return sum;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) discard;
  vec3 x = texelFetch(uPosition, px, 0).xyz;
  float band;
  int k = cacheCascade(x, band);
  if (k == uCascades) discard;  // beyond the largest cascade: no caches, no near field
  vec3 sum = nearLight(k, x, normal.xyz);
  if (band > 0.0) sum = mix(sum, nearLight(k + 1, x, normal.xyz), band);
  vec3 albedo = texelFetch(uAlbedo, px, 0).rgb;
  oRadiance = vec4(albedo * sum / (kPi * kPi), 0.0);
}
