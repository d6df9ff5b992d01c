// The radiance at a specular pixel of a shared cut's entries (cuts/tile_cuts.h) from texel
// `first` of `cuts`, `counts` per tree: each entry's irradiance times the BRDF along its
// direction (glsl/lighting_lightcuts.frag sums Lambert pixels' irradiance alone).
vec3 specularEntries(usamplerBuffer cuts, int first, ivec3 counts, Surface s) {
  vec3 sum = vec3(0.0);
  vec3 l;
  int k;
  for (k = first; k < first + 2 * counts.x; k += 2) {
    vec4 a = uintBitsToFloat(texelFetch(cuts, k));
    float e = max(dot(s.normal, a.xyz), 0.0);
    if (e > 0.0) sum += uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * brdf(s, a.xyz) * e;
  }
  first += 2 * counts.x;
  for (k = first; k < first + 2 * counts.y; k += 2) {
    float e = pointFalloff(uintBitsToFloat(texelFetch(cuts, k)), s.position, s.normal, l);
    if (e > 0.0) sum += uintBitsToFloat(texelFetch(cuts, k + 1)).rgb * brdf(s, l) * e;
  }
  first += 2 * counts.y;
  for (k = first; k < first + 3 * counts.z; k += 3) {
    vec3 e = spotTexelsIrradiance(uintBitsToFloat(texelFetch(cuts, k)),
                                  uintBitsToFloat(texelFetch(cuts, k + 1)),
                                  uintBitsToFloat(texelFetch(cuts, k + 2)), s.position, s.normal, l);
    sum += e * brdf(s, l);
  }
  return sum;
}
