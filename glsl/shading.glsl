// The shading model of scene/shading_model.h (read that file first).

// Unit normal N, view vector V (towards the eye), Phong exponent and colours of a pixel,
// as the G-buffer holds them.
struct Surface {
  vec3 position;
  vec3 normal;
  vec3 view;
  vec3 albedo;
  vec3 specular;
  float exponent;
};

// Radiance per irradiance for a light seen along unit vector l: the bracket of the sum.
vec3 brdf(Surface s, vec3 l) {
  vec3 f = s.albedo / kPi;
  float rv = max(dot(reflect(-l, s.normal), s.view), 0.0);
  return f + s.specular * ((s.exponent + 2.0) / (2.0 * kPi) * pow(rv, s.exponent));
}
