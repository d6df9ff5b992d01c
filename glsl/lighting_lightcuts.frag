// The lightcuts shader's second part, after glsl/lightcuts_walk.glsl (the bounds, the stopping
// rules and a pixel's own walk): exact sums where a cut cannot meet the total rule, the cut
// a pixel shares with its group, and main.
#ifndef DISTANCE
// Under the total rule, a pixel whose cut reached the maximum sums every light instead where
// the renderer allows it (uExactSums: at most kExactLimit lights, render/lightcuts_method.h)
// and they fit the loop budget left (one iteration a light): its error is then float
// rounding, and the rule holds. Lambert pixels sum per light type, as the reference does;
// specular ones in one loop with one shading term: the reference's loops, unrolled per type
// with the BRDF, made llvmpipe take minutes to compile this shader.
uniform int uLightCount;  // lights in the light texture
uniform bool uExactSums;

#define EXACT_E(type, k) (unitIrradiance(type, k, s.position, s.normal, unusedL) * texelFetch(uLights, kTexelsPerLight * (k) + 2).rgb)
#define EXACT_SUM(begin, end, type) for (i = begin; i + 4 <= end; i += 4) { sum += (EXACT_E(type, i) + EXACT_E(type, i + 1)) + (EXACT_E(type, i + 2) + EXACT_E(type, i + 3)); } for (; i < end; ++i) sum += EXACT_E(type, i)

void exactIfAtMax() {
  if (!atMax || !uExactSums || uLightCount + 8 > iterationsLeft) return;
  vec3 sum = vec3(0.0), unusedL;
  int i;
#ifdef HAS_SPECULAR
  if (s.specular != vec3(0.0)) {
    for (i = 0; i < uLightCount; ++i) {
      int type = i < uPointStart ? 0 : (i < uSpotStart ? 1 : 2);
      sum += unitTerm(type, i) * texelFetch(uLights, kTexelsPerLight * i + 2).rgb;
    }
  } else
#endif
  {
    // Lambert: irradiance per type in loops of their own, four lights an iteration (as the
    // reference's), times albedo / π once. With one loop asking each light's type and
    // shading each, 16,384 uniform lights' frame (320×240, every pixel summing) took 2.6 s;
    // with these 1.9 s (the reference 0.8 s, the CPU's cuts 0.5 s of each).
    EXACT_SUM(0, uPointStart, 0);
    EXACT_SUM(uPointStart, uSpotStart, 1);
    EXACT_SUM(uSpotStart, uLightCount, 2);
    sum *= s.albedo / kPi;
    lightEvaluations += uLightCount;
  }
  estimateSum = sum;
  cutSize = uLightCount;
  atMax = false;
}
#endif

#ifdef TILE_CUTS
// The cut this pixel shares with its group, found on the CPU with bounds that hold at every
// pixel of the group (cuts/tile_cuts.h documents it and the texels): sums its
// representatives and checks the stopping rule for this pixel. Returns false, leaving the
// pixel to cut for itself, when it has no shared cut or the rule does not hold here, unless
// the cut is full (kFullCutBit) or the pixel may sum every light (uExactSums): then it takes
// it, counted as at the maximum (atMax), and exactIfAtMax sums every light where it may.
uniform usamplerBuffer uTileCuts;
uniform usampler2D uCutOfPixel;

// Entries hold their representative's direction or position (and 1/range², and a spot's
// cone) themselves, so the loop reads the tile's entries in order instead of lights
// scattered over the light texture. For a Lambert pixel the sum is of irradiance, times
// albedo/π at the end; a specular one weighs each entry by its BRDF (specularEntries). One
// line each: GLSL 3.30 has no line continuation. Two entries per iteration.
#define EMBEDDED_SUM(first, count, TERM) for (k = first; k + 4 <= first + 2 * count; k += 4) { vec4 a0 = uintBitsToFloat(texelFetch(uTileCuts, k)); vec4 c0 = uintBitsToFloat(texelFetch(uTileCuts, k + 1)); vec4 a1 = uintBitsToFloat(texelFetch(uTileCuts, k + 2)); vec4 c1 = uintBitsToFloat(texelFetch(uTileCuts, k + 3)); sum += TERM(a0) * c0.rgb + TERM(a1) * c1.rgb; } if (k < first + 2 * count) { vec4 a0 = uintBitsToFloat(texelFetch(uTileCuts, k)); sum += TERM(a0) * uintBitsToFloat(texelFetch(uTileCuts, k + 1)).rgb; }
#define DIRECTIONAL_T(a) max(dot(s.normal, a.xyz), 0.0)
#define POINT_T(a) pointFalloff(a, s.position, s.normal, unusedL)
vec3 unusedL;

vec3 tileTexel(int k) { return uintBitsToFloat(texelFetch(uTileCuts, k).xyz); }

// The far field's irradiance at this pixel, per channel n · (F + J (x − c)), from its
// texels at k (cuts/far_field.h).
vec3 farField(int k) {
  vec3 d = s.position - tileTexel(k);
  vec3 e;
  for (int c = 0; c < 3; ++c) {
    mat3 j = mat3(tileTexel(k + 4 + 3 * c), tileTexel(k + 5 + 3 * c), tileTexel(k + 6 + 3 * c));
    e[c] = dot(s.normal, tileTexel(k + 1 + c) + j * d);
  }
  return e;
}

bool tileCut() {
  uint c = texelFetch(uCutOfPixel, ivec2(gl_FragCoord.xy), 0).r;
  if (c == kNoSharedCut) return false;
  uvec4 head = texelFetch(uTileCuts, 2 * int(c));
  uvec4 check = texelFetch(uTileCuts, 2 * int(c) + 1);
  vec3 bound = s.albedo * uintBitsToFloat(check.xyz);
  ivec3 counts = ivec3(head.yzw);
  int folded = int(check.w & 0x7fffu);
  int zeros = int((check.w >> 16u) & 0x7fffu);  // entries left out: nothing at any pixel of it
  // A full cut (cuts/tile_cuts.h, RegionCut::full): taken where the rule fails too.
  bool full = (check.w & kFullCutBit) != 0u;
  vec3 sum = vec3(0.0);
  int k;
  int first = int(head.x);
  // A group with specular lobes: its bound per unit specular colour, and its far field's
  // lobes (a constant per unit specular colour), cuts/tile_cuts.h.
  vec3 lobes = vec3(0.0);
  if ((check.w & 0x8000u) != 0u) {
    bound += s.specular * tileTexel(first);
    lobes = s.specular * tileTexel(first + 1);
    first += 2;
  }
  if (folded > 0) {
    sum = farField(first);
    first += kFarFieldTexels;
  }
  int count = counts.x + counts.y + counts.z;
  lightEvaluations += count + min(folded, 1);  // the far field counts as one
#ifdef HAS_SPECULAR
  if (s.specular != vec3(0.0)) {
    sum = sum * (s.albedo / kPi) + lobes + specularEntries(uTileCuts, first, counts, s);
  } else
#endif
  {
    EMBEDDED_SUM(first, counts.x, DIRECTIONAL_T);
    first += 2 * counts.x;
    EMBEDDED_SUM(first, counts.y, POINT_T);
    first += 2 * counts.y;
    for (k = first; k < first + 3 * counts.z; k += 3) {
      sum += spotTexelsIrradiance(uintBitsToFloat(texelFetch(uTileCuts, k)),
                                  uintBitsToFloat(texelFetch(uTileCuts, k + 1)),
                                  uintBitsToFloat(texelFetch(uTileCuts, k + 2)), s.position,
                                  s.normal, unusedL);
    }
    sum *= s.albedo / kPi;
  }
  // The loop iterations either sum ran: two directional or point entries an iteration.
  iterationsLeft -= (counts.x + 1) / 2 + (counts.y + 1) / 2 + counts.z + 6;
  // An exact cut (RegionCut::exact: full, without entries) holds nowhere: exactIfAtMax sums
  // every light for its pixels, as it does for any pixel whose check fails where it may
  // (a walk of its own would cost about as much: render/lightcuts_method.h, kExactLimit).
  bool holds = (count + folded > 0 || !full) && ruleHolds(maxOf(bound), bound, sum);
  full = full || uExactSums;
  if (holds || full) {
    estimateSum = sum;
    cutSize = count + folded + zeros;
    atMax = !holds;
  }
  return holds || full;
}
#endif

// With shared cuts the lighting takes two passes (render/lightcuts_method.cpp). SHARED_PASS:
// the pixels that take their group's cut; the others are discarded, keeping the stencil
// value that sends them to OWN_PASS, which walks their own cuts (the stencil test drops the
// rest before the shader runs). The shared pass's shader then holds no walk, and no block of
// pixels waits on a neighbour's walk.
void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
#if defined(SHARED_PASS)
  if (normal.w == 0.0) {  // background: done (written, so that OWN_PASS leaves it)
    oRadiance = vec4(0.0);
    oCutStats = vec4(0.0);
    return;
  }
#elif !defined(OWN_PASS)
  if (normal.w == 0.0) discard;  // background
#endif
  vec4 position = texelFetch(uPosition, px, 0);
  s.position = position.xyz;
  s.normal = normal.xyz;
  s.view = uOrthographic ? -uForward : normalize(uEye - position.xyz);
  s.albedo = texelFetch(uAlbedo, px, 0).rgb;
  s.specular = texelFetch(uSpecular, px, 0).rgb;
  s.exponent = position.w;
  bool tookTileCut = false;
#ifdef DISTANCE
  cutPass(0.0, 2);
#else
#ifdef TILE_CUTS
  tookTileCut = tileCut();
#endif
#ifdef SHARED_PASS
  if (!tookTileCut) discard;
#else
  if (!tookTileCut) {
    if (uErrorMode == 0) {
      nodeRuleCut();
    } else {
      totalRuleCut();
    }
  }
#endif
  exactIfAtMax();
#endif
  oRadiance = vec4(estimateSum, 0.0);
  int kind = tookTileCut ? (atMax ? kCutStatsSharedCutAtMax : kCutStatsSharedCut)
                         : (atMax ? kCutStatsOwnCutAtMax : kCutStatsOwnCut);
  oCutStats = vec4(float(cutSize), float(lightEvaluations), float(nodeEvaluations), float(kind));
}
