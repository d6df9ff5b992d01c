// Cache c's texel in the caches' textures (render/light_caches.h): (c mod w, c / w) for the
// width w = 2^kCacheTextureShift, by masks and shifts, which llvmpipe runs on every lane at
// once (it divides integers lane by lane).
ivec2 cacheTexel(int c) {
  return ivec2(c & ((1 << kCacheTextureShift) - 1), c >> kCacheTextureShift);
}
