// `--indirect exact` (render/indirect_light.h): one bounce of diffuse light from a
// reflective shadow map's texels, every texel of rows [uFirstRow, uFirstRow + uRows) at every
// pixel, added (blend ONE, ONE) to the radiance target. A texel is a patch of area A
// reflecting flux Φ diffusely (glsl/rsm_flux.frag); it gives the pixel at x with normal n
//   E = Φ · max(n·w, 0) · max(n_t·(−w), 0) / (π · d² · (d² + A/π)),  w = y − x, d = |w|
// (the point-to-patch form factor with 1/d² softened to 1/(d² + A/π), which is exact for a
// disk of area A seen along its axis and keeps a texel beside the pixel finite), and the
// pixel reflects albedo/π · E. No visibility between the texel and the pixel.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uRsmPosition;
uniform sampler2D uRsmNormal;
uniform sampler2D uRsmFlux;
uniform int uRsmSize;
uniform int uFirstRow;
uniform int uRows;

out vec4 oRadiance;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) discard;  // background, or unlit
  vec3 x = texelFetch(uPosition, px, 0).xyz;
  vec3 n = normal.xyz;
  vec3 sum = vec3(0.0);
  for (int row = uFirstRow; row < uFirstRow + uRows; ++row) {
    for (int column = 0; column < uRsmSize; ++column) {
      ivec2 t = ivec2(column, row);
      vec4 flux = texelFetch(uRsmFlux, t, 0);
      if (flux.w == 0.0) continue;
      vec3 w = texelFetch(uRsmPosition, t, 0).xyz - x;
      vec3 nt = texelFetch(uRsmNormal, t, 0).xyz;
      float d2 = max(dot(w, w), kMinDistanceSquared);
      float c = max(dot(n, w), 0.0) * max(-dot(nt, w), 0.0);
      sum += flux.rgb * (c / (d2 * (d2 + flux.w / kPi)));
    }
  }
  vec3 albedo = texelFetch(uAlbedo, px, 0).rgb;
  oRadiance = vec4(albedo * sum / (kPi * kPi), 0.0);
}
