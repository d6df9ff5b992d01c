// A reflective shadow map's flux (render/rsm.h): per texel of the map, the flux its patch of
// surface reflects diffusely, albedo · E · A, E the direct irradiance there from the map's
// light (the shading model's, scene/shading_model.h) and A the patch's area; written over
// the map's radiance target (no blending), with A in w.
//   spot (perspective map):   A = s² cos³θ · d² / cos θ_n, s the texel's edge on the image
//                              plane at unit distance, θ its angle off the map's axis, d its
//                              distance, θ_n the angle between the light and the normal
//   directional (orthographic): A = a / cos θ_n, a the texel's area across the light
// A texel the light does not face reflects nothing.
uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform vec4 uLight0;  // the light's three texels (bake/light_texture_layout.h)
uniform vec4 uLight1;
uniform vec4 uLight2;
uniform bool uDirectional;
uniform vec3 uAxis;          // the map's viewing direction
uniform float uTexelScale;   // spot: s²; directional: a

out vec4 oRadiance;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 normal = texelFetch(uNormal, px, 0);
  if (normal.w == 0.0) {
    oRadiance = vec4(0.0);
    return;
  }
  vec3 p = texelFetch(uPosition, px, 0).xyz;
  vec3 n = normal.xyz;
  vec3 l;
  vec3 e;
  float area;
  if (uDirectional) {
    l = uLight0.xyz;
    e = uLight2.rgb * max(dot(n, l), 0.0);
    area = uTexelScale / max(dot(n, l), 1e-4);
  } else {
    e = spotTexelsIrradiance(uLight0, uLight1, uLight2, p, n, l);
    vec3 toP = p - uLight0.xyz;
    float d2 = max(dot(toP, toP), kMinDistanceSquared);
    float cosAxis = max(dot(toP, uAxis) * inversesqrt(d2), 1e-4);
    area = uTexelScale * cosAxis * cosAxis * cosAxis * d2 / max(dot(n, l), 1e-4);
  }
  vec3 albedo = texelFetch(uAlbedo, px, 0).rgb;
  oRadiance = vec4(albedo * e * area, dot(e, e) > 0.0 ? area : 0.0);
}
