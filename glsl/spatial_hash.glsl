
// Perfect spatial hash lookup (Lefebvre & Hoppe 2006, "Perfect Spatial Hashing"): the slot of
// a key that is in the table, computed bit for bit as hashSlot in bake/spatial_hash.cpp does
// (the hash functions are documented in bake/spatial_hash.h). No key comparison: a key that
// is not in the table gets some slot.

// "lowbias32": a full-avalanche 32-bit integer finaliser.
uint spatialHashMix(uint x) {
  x = (x ^ (x >> 16u)) * 0x7feb352du;
  x = (x ^ (x >> 15u)) * 0x846ca68bu;
  return x ^ (x >> 16u);
}

// The quotient term of h1: linear for salt 0, else a salted hash.
uint spatialHashQuotient(uvec3 q, uint salt) {
  if (salt == 0u) return q.x + 61u * q.y + 3721u * q.z;
  return spatialHashMix(q.x + spatialHashMix(q.y + spatialHashMix(q.z + salt)));
}

// h1: the offset entry of `key` in a table of extent d with `count` entries. The two terms
// are reduced mod count before the sum, so it cannot wrap.
uint spatialHashEntry(uvec3 key, uvec3 d, uint count, uint salt) {
  uvec3 r = key % d;
  uint mixed = spatialHashMix(r.x + d.x * (r.y + d.y * r.z));
  return (mixed % count + spatialHashQuotient(key / d, salt) % count) % count;
}

// The slot index of `key` (components < 2^21): (key + offset) mod dims, linearised x first.
// The offset table is a run of offsetCount RGBA16UI texels from offsetBase, (x, y, z, w);
// the first texel's w is the table's salt.
uint spatialHashSlot(uvec3 key, ivec3 dims, int offsetCount, usamplerBuffer offsets, int offsetBase) {
  uvec3 d = uvec3(dims);
  uint salt = texelFetch(offsets, offsetBase).w;
  uint entry = spatialHashEntry(key, d, uint(offsetCount), salt);
  uvec3 s = (key + texelFetch(offsets, offsetBase + int(entry)).xyz) % d;
  return s.x + d.x * (s.y + d.y * s.z);
}
