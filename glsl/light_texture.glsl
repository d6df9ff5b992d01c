
// Reads lights from the light texture; the layout is documented in
// bake/light_texture_layout.h.
uniform samplerBuffer uLights;

// Irradiance at s.position from light i, and the unit vector l towards it.
vec3 lightIrradiance(int i, vec3 p, vec3 n, out vec3 l) {
  vec4 a = texelFetch(uLights, 3 * i);
  vec4 b = texelFetch(uLights, 3 * i + 1);
  vec4 c = texelFetch(uLights, 3 * i + 2);
  vec3 toLight = a.xyz - p * step(0.0, a.w);  // directional: a.xyz is already the unit vector
  float d2 = max(dot(toLight, toLight), kMinDistanceSquared);
  l = toLight * inversesqrt(d2);
  float x = d2 * max(a.w, 0.0);  // (d / range)², 0 without range
  float window = clamp(1.0 - x * x, 0.0, 1.0);
  float t = clamp(dot(-l, b.xyz) * b.w + c.w, 0.0, 1.0);
  float cone = t * t * (3.0 - 2.0 * t);
  return c.rgb * (max(dot(n, l), 0.0) * window * window * cone / d2);
}
