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
  vec3 sum = vec3(0.0);
  vec3 l;
  if (s.specular == vec3(0.0)) {
    // Pure Lambert (the default material): the BRDF is constant, so sum irradiance only.
    for (int i = uFirstLight; i < end; ++i) sum += lightIrradiance(i, s.position, s.normal, l);
    sum *= s.albedo / kPi;
  } else {
    for (int i = uFirstLight; i < end; ++i) {
      vec3 e = lightIrradiance(i, s.position, s.normal, l);
      sum += brdf(s, l) * e;
    }
  }
  oRadiance = vec4(sum, 0.0);
}
