// Blended primitives: one lit layer (the G-buffer's radiance target, after the lighting
// method ran over the layer's pixels) composited over the frame so far with the layer's alpha
// (blend SRC_ALPHA, ONE_MINUS_SRC_ALPHA; alpha ONE, ONE_MINUS_SRC_ALPHA).
uniform sampler2D uRadiance;
uniform sampler2D uAlbedo;  // w: alpha

out vec4 oColour;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 radiance = texelFetch(uRadiance, px, 0);
  if (radiance.w == 0.0) discard;  // not covered by the layer
  oColour = vec4(radiance.rgb, clamp(texelFetch(uAlbedo, px, 0).w, 0.0, 1.0));
}
