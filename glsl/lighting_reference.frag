// The reference method: every light of [uFirstLight, uFirstLight + uLightCount) at every
// pixel, added (blend ONE, ONE) to the radiance target. Long light lists are split into
// several such passes by the C++ side; nothing here depends on the light count.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uSpecular;
uniform vec3 uEye;
uniform vec3 uForward;
uniform bool uOrthographic;
uniform int uFirstLight;
uniform int uLightCount;

out vec4 oRadiance;

// Radiance from one light of each type: BRDF × irradiance.
vec3 directionalRadiance(int i, Surface s) {
  vec3 l;
  vec3 e = directionalIrradiance(i, s.normal, l);
  return brdf(s, l) * e;
}
vec3 pointRadiance(int i, Surface s) {
  vec3 l;
  vec3 e = pointIrradiance(i, s.position, s.normal, l);
  return brdf(s, l) * e;
}
vec3 spotRadiance(int i, Surface s) {
  vec3 l;
  vec3 e = spotIrradiance(i, s.position, s.normal, l);
  return brdf(s, l) * e;
}

vec3 unusedL;
#define DIRECTIONAL_E(k) directionalIrradiance(k, s.normal, unusedL)
#define POINT_E(k) pointIrradiance(k, s.position, s.normal, unusedL)
#define SPOT_E(k) spotIrradiance(k, s.position, s.normal, unusedL)
#define DIRECTIONAL_L(k) directionalRadiance(k, s)
#define POINT_L(k) pointRadiance(k, s)
#define SPOT_L(k) spotRadiance(k, s)

// sum += TERM(i) for i in [begin, end), unrolled by four: llvmpipe pays a mask update per
// iteration of a loop whose bounds it cannot see, so fewer iterations run faster. (One line:
// GLSL 3.30 has no line continuation.)
#define SUM_LIGHTS(begin, end, TERM) for (i = begin; i + 4 <= end; i += 4) { sum += (TERM(i) + TERM(i + 1)) + (TERM(i + 2) + TERM(i + 3)); } for (; i < end; ++i) sum += TERM(i)

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) discard;  // background
  vec4 position = texelFetch(uPosition, px, 0);
  Surface s;
  s.position = position.xyz;
  s.normal = normal.xyz;
  s.view = uOrthographic ? -uForward : normalize(uEye - position.xyz);
  s.albedo = texelFetch(uAlbedo, px, 0).rgb;
  s.specular = texelFetch(uSpecular, px, 0).rgb;
  s.exponent = position.w;

  int end = uFirstLight + uLightCount;
  int pointStart = clamp(uPointStart, uFirstLight, end);
  int spotStart = clamp(uSpotStart, uFirstLight, end);
  vec3 sum = vec3(0.0);
  int i;
  // Variants (#defines from C++) leave out the loops for light types the scene lacks and
  // the specular path when no material has a specular term: the driver compiles less.
#ifdef HAS_SPECULAR
  if (s.specular != vec3(0.0)) {
#ifdef HAS_DIRECTIONAL
    SUM_LIGHTS(uFirstLight, pointStart, DIRECTIONAL_L);
#endif
#ifdef HAS_POINT
    SUM_LIGHTS(pointStart, spotStart, POINT_L);
#endif
#ifdef HAS_SPOT
    SUM_LIGHTS(spotStart, end, SPOT_L);
#endif
    oRadiance = vec4(sum, 0.0);
    return;
  }
#endif
  // Pure Lambert (the default material): the BRDF is constant, so sum irradiance only.
#ifdef HAS_DIRECTIONAL
  SUM_LIGHTS(uFirstLight, pointStart, DIRECTIONAL_E);
#endif
#ifdef HAS_POINT
  SUM_LIGHTS(pointStart, spotStart, POINT_E);
#endif
#ifdef HAS_SPOT
  SUM_LIGHTS(spotStart, end, SPOT_E);
#endif
  sum *= s.albedo / kPi;
  oRadiance = vec4(sum, 0.0);
}
