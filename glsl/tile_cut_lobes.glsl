// The radiance at a specular pixel of a shared cut's entries (cuts/tile_cuts.h) from texel
// `first` of `cuts`, `counts` per tree: each entry's irradiance times the BRDF along its
// direction (glsl/lighting_lightcuts.frag sums Lambert pixels' irradiance alone). brdf() of
// shading.glsl is summed in two parts, the irradiance (times albedo/π at the end) and the
// irradiance times max(l·m, 0)^n, m the view's mirror direction (times the lobe's constant
// at the end): l·m is R·V for R = reflect(−l, N). Two entries per iteration, as the Lambert
// sum: a software rasteriser pays for each loop iteration.
#define LOBE_SUM(ce, l) { vec3 c_ = ce; irradiance += c_; lobe += c_ * pow(max(dot(l, m), 0.0), s.exponent); }
vec3 specularEntries(usamplerBuffer cuts, int first, ivec3 counts, Surface s) {
  vec3 m = reflect(-s.view, s.normal);
  vec3 irradiance = vec3(0.0), lobe = vec3(0.0);
  vec3 l0, l1;
  int k;
  for (k = first; k + 4 <= first + 2 * counts.x; k += 4) {
    vec4 a0 = uintBitsToFloat(texelFetch(cuts, k));
    vec4 a1 = uintBitsToFloat(texelFetch(cuts, k + 2));
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * max(dot(s.normal, a0.xyz), 0.0), a0.xyz);
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 3)).rgb * max(dot(s.normal, a1.xyz), 0.0), a1.xyz);
  }
  if (k < first + 2 * counts.x) {
    vec4 a0 = uintBitsToFloat(texelFetch(cuts, k));
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * max(dot(s.normal, a0.xyz), 0.0), a0.xyz);
  }
  first += 2 * counts.x;
  for (k = first; k + 4 <= first + 2 * counts.y; k += 4) {
    float e0 = pointFalloff(uintBitsToFloat(texelFetch(cuts, k)), s.position, s.normal, l0);
    float e1 = pointFalloff(uintBitsToFloat(texelFetch(cuts, k + 2)), s.position, s.normal, l1);
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * e0, l0);
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 3)).rgb * e1, l1);
  }
  if (k < first + 2 * counts.y) {
    float e0 = pointFalloff(uintBitsToFloat(texelFetch(cuts, k)), s.position, s.normal, l0);
    LOBE_SUM(uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * e0, l0);
  }
  first += 2 * counts.y;
  for (k = first; k < first + 3 * counts.z; k += 3) {
    vec3 e = spotTexelsIrradiance(uintBitsToFloat(texelFetch(cuts, k)),
                                  uintBitsToFloat(texelFetch(cuts, k + 1)),
                                  uintBitsToFloat(texelFetch(cuts, k + 2)), s.position, s.normal, l0);
    LOBE_SUM(e, l0);
  }
  return irradiance * (s.albedo / kPi) + lobe * (s.specular * ((s.exponent + 2.0) / (2.0 * kPi)));
}
#undef LOBE_SUM
