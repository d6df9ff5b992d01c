
// Reads lights from the light texture; the layout is documented in
// bake/light_texture_layout.h.
uniform samplerBuffer uLights;

// Lights are stored by type: directional in [0, uPointStart), point in
// [uPointStart, uSpotStart), spot from uSpotStart on, so each loop evaluates only what its
// type needs (a point light skips the cone, a directional light the distance).
uniform int uPointStart;
uniform int uSpotStart;

// Irradiance from directional light i, and the unit vector l towards it.
vec3 directionalIrradiance(int i, vec3 n, out vec3 l) {
  vec4 a = texelFetch(uLights, kTexelsPerLight * i);
  vec4 c = texelFetch(uLights, kTexelsPerLight * i + 2);
  l = a.xyz;
  return c.rgb * max(dot(n, l), 0.0);
}

// cos θ · window / d² at p for a light at a.xyz with a.w = 1/range², and the unit vector l.
float pointFalloff(vec4 a, vec3 p, vec3 n, out vec3 l) {
  vec3 toLight = a.xyz - p;
  float d2 = max(dot(toLight, toLight), kMinDistanceSquared);
  float invD = inversesqrt(d2);
  l = toLight * invD;
  float x = d2 * a.w;  // (d / range)², 0 without range
  float window = clamp(1.0 - x * x, 0.0, 1.0);
  return max(dot(n, l), 0.0) * window * invD * invD;
}

// Irradiance at p from point light i, and l.
vec3 pointIrradiance(int i, vec3 p, vec3 n, out vec3 l) {
  vec4 a = texelFetch(uLights, kTexelsPerLight * i);
  vec4 c = texelFetch(uLights, kTexelsPerLight * i + 2);
  return c.rgb * pointFalloff(a, p, n, l);
}

// The spot cone's smoothstep for light direction l, from texel 1 (b) and the cone offset.
float spotCone(vec4 b, float offset, vec3 l) {
  float t = clamp(dot(-l, b.xyz) * b.w + offset, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Irradiance at p from a spot light given by its three texels a, b, c: the point light's,
// times the cone's smoothstep. (A shared tile cut's spot entry has the same texels, with the
// node's intensity in c.rgb.)
vec3 spotTexelsIrradiance(vec4 a, vec4 b, vec4 c, vec3 p, vec3 n, out vec3 l) {
  return c.rgb * (pointFalloff(a, p, n, l) * spotCone(b, c.w, l));
}

// Irradiance at p from spot light i.
vec3 spotIrradiance(int i, vec3 p, vec3 n, out vec3 l) {
  return spotTexelsIrradiance(texelFetch(uLights, kTexelsPerLight * i), texelFetch(uLights, kTexelsPerLight * i + 1),
                              texelFetch(uLights, kTexelsPerLight * i + 2), p, n, l);
}

// Irradiance per unit colour · intensity at p from light i of type `type` (0 directional,
// 1 point, 2 spot), and l: what a light tree node's intensity multiplies.
float unitIrradiance(int type, int i, vec3 p, vec3 n, out vec3 l) {
  vec4 a = texelFetch(uLights, kTexelsPerLight * i);
  if (type == 0) {
    l = a.xyz;
    return max(dot(n, l), 0.0);
  }
  float f = pointFalloff(a, p, n, l);
  if (type == 2 && f > 0.0) {
    f *= spotCone(texelFetch(uLights, kTexelsPerLight * i + 1), texelFetch(uLights, kTexelsPerLight * i + 2).w, l);
  }
  return f;
}
