// `--indirect caches` (render/light_caches.h): the caches a frame keeps from the one before
// (LightCaches::upload) take their coefficients from the previous frame's targets. Cache c
// (texel (c mod width, c / width)) below uKept reads uPrevious at its own texel: its slot in
// the previous targets, laid out alike.
uniform sampler2D uPrevious;
uniform int uKept;
uniform sampler2D uSh0;
uniform sampler2D uSh1;
uniform sampler2D uSh2;
uniform sampler2D uSh3;
uniform sampler2D uSh4;
uniform sampler2D uSh5;
uniform sampler2D uSh6;
uniform sampler2D uCorrection;

out vec4 oSh0;
out vec4 oSh1;
out vec4 oSh2;
out vec4 oSh3;
out vec4 oSh4;
out vec4 oSh5;
out vec4 oSh6;
out vec4 oCorrection;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  if ((px.y << kCacheTextureShift) + px.x >= uKept) discard;
  int slot = int(texelFetch(uPrevious, px, 0).r);
  ivec2 at = cacheTexel(slot);
  oSh0 = texelFetch(uSh0, at, 0);
  oSh1 = texelFetch(uSh1, at, 0);
  oSh2 = texelFetch(uSh2, at, 0);
  oCorrection = texelFetch(uCorrection, at, 0);
#ifdef SH_L2
  oSh3 = texelFetch(uSh3, at, 0);
  oSh4 = texelFetch(uSh4, at, 0);
  oSh5 = texelFetch(uSh5, at, 0);
  oSh6 = texelFetch(uSh6, at, 0);
#else
  oSh3 = vec4(0.0);
  oSh4 = vec4(0.0);
  oSh5 = vec4(0.0);
  oSh6 = vec4(0.0);
#endif
}
