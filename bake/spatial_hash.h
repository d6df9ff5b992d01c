#pragma once
// Perfect spatial hashing with 3-D offset vectors, after Lefebvre & Hoppe, "Perfect Spatial
// Hashing" (SIGGRAPH 2006). A key k (an integer cell coordinate) goes to slot
//   s = (k + offsets[h1(k)]) mod dims   (componentwise),  index = s.x + a (s.y + b s.z),
// and the offsets are chosen so that distinct keys get distinct slots. glsl/spatial_hash.glsl
// computes the same slot, bit for bit, in uint32 arithmetic.
//
// h1 (the offset entry) splits k into its residue r = k mod dims and quotient q = k / dims:
//   h1(k) = (mix(r.x + a (r.y + b r.z)) mod R + (q.x + 61 q.y + 3721 q.z) mod R) mod R,
// mix being the "lowbias32" integer finaliser. Two keys with the same residue reach the same
// slot whatever the offset, so they must not share an entry; for those the mix terms are
// equal and the entries differ by their quotients' linear index mod R. That index does not
// wrap in uint32 when every dims component is >= 2 (every near-cubic table), and then is never
// 0 mod R when the quotients differ by at most 30 per axis and R > 113490, or by at most 1 per
// axis and R > 3783: clustered keys, a few table widths across, never share such an entry.
// For keys spread further the construction checks and retries with another R. Where no R
// can separate two keys (equal quotient terms) the quotient term becomes a salted hash,
// mix(q.x + mix(q.y + mix(q.z + salt))), with the salt (1..65535) in the w of the offset
// table's first texel; salt 0 is the linear term.
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>
#include <vector>

namespace manylight {

struct SpatialHash {
  glm::ivec3 dims{1};                 // hash table extent (a, b, c); slots = a*b*c
  int offsetCount = 1;                // R: entries of the offset table
  std::vector<glm::u16vec3> offsets;  // R entries, each component < the matching dims component
  std::vector<std::uint32_t> slots;   // per key (input order), its slot index
  int attempts = 1;                   // constructions tried until one succeeded (for --stats)
  std::uint16_t salt = 0;             // 0: linear quotient term of h1, else its salt (above)
  std::size_t slotCount() const;      // a*b*c
};

// Largest key component the hash takes: keys are cell coordinates below 2^21.
constexpr std::uint32_t kSpatialHashKeyLimit = 1u << 21;

// A perfect hash of `keys`: distinct cell coordinates, each component < 2^21. slotCount() is
// in [n, 1.1 n] for n >= 1 keys (for n = 0: one slot, no keys); each dims component is at
// most 65536. Deterministic (fixed seed). A failed construction is retried with a larger
// offset table, and past a few failures a slightly larger table, so valid input never throws.
// Throws BakeError for a key component >= 2^21 or two equal keys.
SpatialHash buildSpatialHash(const std::vector<glm::uvec3>& keys);

// The offset-table entry h1(key) (see above).
std::uint32_t spatialHashEntry(const SpatialHash& h, glm::uvec3 key);

// The slot of `key` (exactly what the GLSL function computes).
std::uint32_t hashSlot(const SpatialHash& h, glm::uvec3 key);

// The offset table as RGBA16UI texels (x, y, z, w), 4 values per entry, for the
// usamplerBuffer glsl/spatial_hash.glsl reads: w is the salt in the first texel, else 0.
std::vector<std::uint16_t> spatialHashTexels(const SpatialHash& h);

}  // namespace manylight
