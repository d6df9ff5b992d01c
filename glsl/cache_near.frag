// `--indirect caches`, the near field (render/near_field.h): every map texel within twice its
// near radius r of the pixel lights it as glsl/indirect_exact.frag's kernel times
// 1 − farWeight (the caches carry the rest), added (blend ONE, ONE) to the radiance target.
// r is the larger of the texel's map radius and kNearCells cells of the pixel's cascade; in a
// transition band the near light of both cascades is blended as the caches are. The stencil
// (render/pixel_classes.h) picks the pixels: covered ones within the cascades. The texels
// come in entries, clusters or texels alone, found in the cascade's grid: the cells listed for
// the pixel's own cell that lie within the grid's reach of the pixel, and of those only the
// [uFirst[k], uFirst[k] + uCount[k]) th entries in the cells' order are read, so one pass
// stays under llvmpipe's 65,535 loop iterations. A pixel farther from a flat cluster than
// kRsmClusterDistance of its radii takes its light as one texel's at its centre; nearer, it
// sums the cluster's texels.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
// Per cascade, its entries ordered by the cascade's grid cell, then the clusters' texels,
// kRsmClusterEdge² a cluster (those that reflect nothing of flux 0), each a record of:
uniform sampler2D uEntryCentre;  // xyz, radius (0: a texel alone)
// Mean unit normal; a texel's area, or a cluster's first texel record (a cluster counts as
// one texel only from kRsmClusterDistance radii, where its area's softening is left out)
uniform sampler2D uEntryNormal;
// Σ flux, the map's near radius; negative where the cluster's texels do not share its facing
uniform sampler2D uEntryFlux;
// Per cascade's cell (stacked in z): its neighbours' count, first in uNeighbours, and count
// before those wholly on its plane
uniform sampler3D uGrid;
// Per cell, the cells holding entries whose texels lie within 2r of the cell's box (r the
// cascade's largest near radius; render/near_grid.h), those a pixel in the cell reads, each as
// (x | y << 8 | z << 16 within the cascade, its first entry, their count, how many come
// before those whose texels all lie on its plane)
uniform sampler2D uNeighbours;
// and the plane the most of its texels share (n, n·p), or 0
uniform sampler2D uNeighbourPlanes;
uniform vec3 uGridOrigin;
uniform float uGridCell[8];
uniform float uGridReach[8];   // per cascade, the farthest an entry's light reaches
uniform float uGridSpread[8];  // per cascade, the largest entry's radius: its texels' reach
                               // past its cell
uniform ivec3 uGridCells[8];
uniform int uGridFirstZ[8];
uniform int uFirst[8];
uniform int uCount[8];

out vec4 oRadiance;

ivec2 texelAt(int i) {
  return ivec2(i & ((1 << kNearTextureShift) - 1), i >> kNearTextureShift);
}

// The near light of a texel (flux.rgb, area flux.w) at y, of normal nt, arriving at x of
// normal n for a near radius r.
vec3 texelLight(vec4 flux, vec3 y, vec3 nt, vec3 x, vec3 n, float r) {
  vec3 w = y - x;
  float d2 = max(dot(w, w), kMinDistanceSquared);
  if (d2 >= 4.0 * r * r) return vec3(0.0);
  float c = max(dot(n, w), 0.0) * max(-dot(nt, w), 0.0);
  float near = 1.0 - farWeight(sqrt(d2), r);
  return flux.rgb * (near * c / (d2 * (d2 + flux.w / kPi)));
}

// Σ over cell entries [first, last) from `base`. Each iteration reads one record, an entry or
// a texel of the cluster being summed, and adds at most one texel's light: straight-line code
// in one loop, since llvmpipe runs the body of a branch or inner loop that no lane takes
// for every entry all the same.
vec3 cellLight(int base, int first, int last, vec3 x, vec3 n, float cascadeRadius) {
  vec3 sum = vec3(0.0);
  int j = first;
  int texel = 0, texels = 0;  // of the cluster being summed texel by texel
  while (j < last) {
    ivec2 e = texelAt(texels > 0 ? texel : base + j);
    vec4 centre = texelFetch(uEntryCentre, e, 0);
    vec4 flux = texelFetch(uEntryFlux, e, 0);
    vec4 na = texelFetch(uEntryNormal, e, 0);
    float r = max(abs(flux.w), cascadeRadius);
    float d = length(centre.xyz - x);
    bool cluster = centre.w > 0.0;
    // A cluster within reach that is not flat, or nearer than kRsmClusterDistance radii.
    bool expand = texels == 0 && cluster && d - centre.w < 2.0 * r &&
                  (flux.w < 0.0 || d < kRsmClusterDistance * centre.w);
    if (!expand)
      sum += texelLight(vec4(flux.rgb, cluster ? 0.0 : na.w), centre.xyz, na.xyz, x, n, r);
    if (expand) {
      texel = int(na.w);
      texels = kRsmClusterEdge * kRsmClusterEdge;
    } else if (texels > 0) {
      ++texel;
      if (--texels == 0) ++j;
    } else {
      ++j;
    }
  }
  return sum;
}

// Σ over the near entries of cascade k's grid: the irradiance times π.
vec3 nearLight(int k, vec3 x, vec3 n) {
  ivec3 home = clamp(ivec3(floor((x - uGridOrigin) / uGridCell[k])), ivec3(0), uGridCells[k] - 1);
  vec3 homeCell = texelFetch(uGrid, home + ivec3(0, 0, uGridFirstZ[k]), 0).rgb;
  int neighbours = int(homeCell.x);
  int firstNeighbour = int(homeCell.y);
  float cascadeRadius = kNearCells * uCell[k];
  int seen = 0;  // entries of the cells before this one
  float tolerance = kPlaneTolerance * uGridCell[k];
  // The listed cells wholly on one plane come last (render/near_grid.h, homePlanes): in or
  // behind it, x skips them all, as it would each by its own plane below.
  int offPlane = int(homeCell.z);
  if (offPlane < neighbours) {
    vec4 plane = texelFetch(uNeighbourPlanes, texelAt(firstNeighbour + offPlane), 0);
    if (dot(plane.xyz, x) - plane.w <= tolerance) neighbours = offPlane;
  }
  float reach = uGridReach[k];
  vec3 sum = vec3(0.0);
  for (int i = 0; i < neighbours; ++i) {
    vec4 listed = texelFetch(uNeighbours, texelAt(firstNeighbour + i), 0);
    int cellBits = int(listed.x);
    ivec3 at = ivec3(cellBits & 255, (cellBits >> 8) & 255, cellBits >> 16);
    int count = int(listed.z);
    vec3 boxLo = uGridOrigin + vec3(at) * uGridCell[k];
    vec3 outside = max(max(boxLo - x, x - boxLo - uGridCell[k]), 0.0);
    vec3 centre = boxLo + 0.5 * uGridCell[k] - x;
    if (dot(outside, outside) >= reach * reach ||
        dot(n, centre) + 0.5 * uGridCell[k] * dot(abs(n), vec3(1.0)) + uGridSpread[k] <= 0.0) {
      // Beyond every texel's reach, or with all its entries' texels behind x's surface: no
      // light from it.
      count = 0;
    } else {
      // In or behind the plane of the cell's last entries' texels, x gets no light from
      // them: each sends its light to the side its normal faces.
      vec4 plane = texelFetch(uNeighbourPlanes, texelAt(firstNeighbour + i), 0);
      if (plane.xyz != vec3(0.0) && dot(plane.xyz, x) - plane.w <= tolerance)
        count = int(listed.w);
    }
    int first = max(uFirst[k] - seen, 0), last = min(uFirst[k] + uCount[k] - seen, count);
    sum += cellLight(int(listed.y), first, last, x, n, cascadeRadius);
    seen += int(listed.z);
  }
  return sum;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 x = texelFetch(uPosition, px, 0).xyz;
  float band;
  int k = cacheCascade(x, band);
  // Beyond the largest cascade, where the CPU's classes and this differ by a rounding: no
  // caches, no near field. (Here a discard measured faster than a share of 0 on llvmpipe; the
  // interpolation's was the other way round.)
  if (k >= uCascades) discard;
  vec3 n = texelFetch(uNormal, px, 0).xyz;
  vec3 sum = nearLight(k, x, n);
  if (band > 0.0) sum = mix(sum, nearLight(k + 1, x, n), band);
  vec3 albedo = texelFetch(uAlbedo, px, 0).rgb;
  oRadiance = vec4(albedo * sum / (kPi * kPi), 0.0);
}
