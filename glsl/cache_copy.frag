// `--indirect caches` (render/light_caches.h): the caches a frame keeps from the one before
// (LightCaches::upload) take their coefficients from a map's targets of the frame before.
// Cache c (texel (c mod width, c / width)) below uKept reads uPrevious at its own texel: its
// slot in those targets, laid out alike. With CACHE_SUM, every cache below uKept reads its own
// slot, and the pass, blended (ONE, ONE), adds a map's coefficients to the sum over maps.
#ifndef CACHE_SUM
uniform sampler2D uPrevious;
#endif
uniform int uKept;
uniform sampler2D uSh0;
uniform sampler2D uSh1;
uniform sampler2D uSh2;
uniform sampler2D uSh3;
uniform sampler2D uSh4;
uniform sampler2D uSh5;
uniform sampler2D uSh6;
uniform sampler2D uExact;

out vec4 oSh0;
out vec4 oSh1;
out vec4 oSh2;
out vec4 oSh3;
out vec4 oSh4;
out vec4 oSh5;
out vec4 oSh6;
out vec4 oExact;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  if ((px.y << kCacheTextureShift) + px.x >= uKept) discard;
#ifdef CACHE_SUM
  ivec2 at = px;
#else
  ivec2 at = cacheTexel(int(texelFetch(uPrevious, px, 0).r));
#endif
  oSh0 = texelFetch(uSh0, at, 0);
  oSh1 = texelFetch(uSh1, at, 0);
  oSh2 = texelFetch(uSh2, at, 0);
  oExact = texelFetch(uExact, at, 0);
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
