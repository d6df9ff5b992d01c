// `--indirect` (render/rsm_choice.h): per light of the light texture (fragment i at
// (i mod width, i / width)), Σ over the sampled pixels of the luminance of its irradiance
// there, written to an R32F target that is read back to choose the lights given maps.
uniform sampler2D uSamples;  // column s: row 0 the sample's position, row 1 its unit normal
uniform int uSampleCount;
uniform int uLightCount;

out vec4 oFlux;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  int i = px.y * kRsmChoiceWidth + px.x;
  if (i >= uLightCount) discard;
  const vec3 kLuminance = vec3(0.2126, 0.7152, 0.0722);
  vec3 l;
  float sum = 0.0;
  for (int s = 0; s < uSampleCount; ++s) {
    vec3 p = texelFetch(uSamples, ivec2(s, 0), 0).xyz;
    vec3 n = texelFetch(uSamples, ivec2(s, 1), 0).xyz;
    vec3 e = i < uPointStart ? directionalIrradiance(i, n, l)
             : i < uSpotStart ? pointIrradiance(i, p, n, l)
                              : spotIrradiance(i, p, n, l);
    sum += dot(e, kLuminance);
  }
  oFlux = vec4(sum, 0.0, 0.0, 0.0);
}
