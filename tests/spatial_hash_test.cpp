// Perfect spatial hashing (bake/spatial_hash.h): every key set of every size gets distinct
// slots in a table of at most 1.1 n, hashSlot agrees with the built slots, offsets fit the
// table, builds are deterministic, and bad input is rejected with its reason.
#include "bake/spatial_hash.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <unordered_set>

#include "bake/colour_fit.h"  // BakeError

namespace manylight {
namespace {

std::uint64_t packKey(glm::uvec3 k) {
  return std::uint64_t(k.x) | std::uint64_t(k.y) << 21 | std::uint64_t(k.z) << 42;
}

// n distinct keys drawn uniformly from base + [0, extent)^3.
std::vector<glm::uvec3> randomKeys(std::size_t n, std::uint32_t extent, glm::uvec3 base,
                                   std::uint32_t seed) {
  std::mt19937 random(seed);
  std::unordered_set<std::uint64_t> seen;
  std::vector<glm::uvec3> keys;
  while (keys.size() < n) {
    const glm::uvec3 k = base + glm::uvec3(random() % extent, random() % extent, random() % extent);
    if (seen.insert(packKey(k)).second) keys.push_back(k);
  }
  return keys;
}

// Sparse: anywhere in the key domain.
std::vector<glm::uvec3> scatteredKeys(std::size_t n) {
  return randomKeys(n, kSpatialHashKeyLimit, glm::uvec3(0), 7);
}

// Clustered like octree cells: an eighth of the cells of a cube 2 table widths across.
std::vector<glm::uvec3> clusteredKeys(std::size_t n) {
  const auto extent = std::uint32_t(std::ceil(std::cbrt(8.0 * double(n)))) + 1;
  return randomKeys(n, extent, glm::uvec3(1000, 2000, 3000), 11);
}

// All cells of three slabs 4 cells thick, 40 cells apart.
std::vector<glm::uvec3> slabKeys(std::size_t n) {
  const auto side = std::uint32_t(std::ceil(std::sqrt(double(n) / 12.0)));
  std::vector<glm::uvec3> keys;
  for (std::uint32_t z = 0; keys.size() < n; ++z) {
    for (std::uint32_t y = 0; y < side && keys.size() < n; ++y) {
      for (std::uint32_t x = 0; x < side && keys.size() < n; ++x) {
        keys.push_back({x + 5, y + 9, (z / 4) * 40 + z % 4});
      }
    }
  }
  return keys;
}

std::vector<glm::uvec3> lineKeys(std::size_t n, std::uint32_t step) {
  std::vector<glm::uvec3> keys;
  for (std::uint32_t i = 0; i < n; ++i) keys.push_back({7, i * step, 3});
  return keys;
}

std::vector<glm::uvec3> planeKeys(std::uint32_t side, std::uint32_t step) {
  std::vector<glm::uvec3> keys;
  for (std::uint32_t y = 0; y < side; ++y) {
    for (std::uint32_t x = 0; x < side; ++x) keys.push_back({x * step, 12, y * step});
  }
  return keys;
}

void expectPerfect(const std::vector<glm::uvec3>& keys, const std::string& what) {
  SCOPED_TRACE(what + ", " + std::to_string(keys.size()) + " keys");
  const SpatialHash h = buildSpatialHash(keys);
  const std::size_t n = keys.size();
  EXPECT_GE(h.slotCount(), n);
  EXPECT_LE(h.slotCount(), n + n / 10);
  EXPECT_LE(std::max(h.dims.x, std::max(h.dims.y, h.dims.z)), 65536);
  ASSERT_EQ(h.offsets.size(), std::size_t(h.offsetCount));
  for (glm::u16vec3 o : h.offsets) {
    ASSERT_TRUE(glm::all(glm::lessThan(glm::ivec3(o), h.dims))) << o.x << " " << o.y << " " << o.z;
  }
  ASSERT_EQ(h.slots.size(), n);
  std::vector<bool> taken(h.slotCount(), false);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_LT(h.slots[i], h.slotCount());
    ASSERT_FALSE(taken[h.slots[i]]) << "key " << i << " shares slot " << h.slots[i];
    taken[h.slots[i]] = true;
    ASSERT_EQ(hashSlot(h, keys[i]), h.slots[i]) << "key " << i;
  }
  EXPECT_GE(h.attempts, 1);
}

const std::size_t kSizes[] = {1, 2, 7, 8, 9, 100, 1000, 100000};

TEST(SpatialHash, ScatteredKeysGetDistinctSlots) {
  for (std::size_t n : kSizes) expectPerfect(scatteredKeys(n), "scattered");
}

TEST(SpatialHash, ClusteredKeysGetDistinctSlots) {
  for (std::size_t n : kSizes) expectPerfect(clusteredKeys(n), "clustered");
}

TEST(SpatialHash, SlabKeysGetDistinctSlots) {
  for (std::size_t n : kSizes) expectPerfect(slabKeys(n), "slabs");
}

TEST(SpatialHash, KeysOnALineOrAPlaneGetDistinctSlots) {
  for (std::size_t n : kSizes) expectPerfect(lineKeys(n, 1), "line");
  expectPerfect(lineKeys(1000, 64), "line, step 64");
  expectPerfect(lineKeys(100000, 20), "line, step 20");
  for (std::uint32_t side : {1u, 3u, 10u, 31u, 300u}) expectPerfect(planeKeys(side, 1), "plane");
  expectPerfect(planeKeys(100, 16), "plane, step 16");
}

TEST(SpatialHash, KeysNearTheDomainLimitGetDistinctSlots) {
  const std::uint32_t top = kSpatialHashKeyLimit - 1;
  expectPerfect({glm::uvec3(top)}, "corner");
  expectPerfect({glm::uvec3(top), glm::uvec3(0), glm::uvec3(top, 0, top)}, "corners");
  for (std::size_t n : {9u, 1000u, 100000u}) {
    const auto extent = std::uint32_t(std::ceil(std::cbrt(2.0 * double(n)))) + 1;
    expectPerfect(randomKeys(n, extent, glm::uvec3(kSpatialHashKeyLimit - extent), 3), "top");
  }
}

// Tiny key counts get a table that fits exactly (7 is prime; 9 has no near-cube), larger ones
// the smallest near-cube (c <= 2a) of at least n slots; the larger tables that follow failed
// constructions are not reached by these sets.
TEST(SpatialHash, TablesAreTheSmallestNearCubeOrAnExactFit) {
  EXPECT_EQ(buildSpatialHash(clusteredKeys(1)).dims, glm::ivec3(1, 1, 1));
  EXPECT_EQ(buildSpatialHash(clusteredKeys(7)).dims, glm::ivec3(1, 1, 7));
  EXPECT_EQ(buildSpatialHash(clusteredKeys(8)).dims, glm::ivec3(2, 2, 2));
  EXPECT_EQ(buildSpatialHash(clusteredKeys(9)).dims, glm::ivec3(1, 3, 3));
  EXPECT_EQ(buildSpatialHash(lineKeys(100, 1)).dims, glm::ivec3(4, 5, 5));
  EXPECT_EQ(buildSpatialHash(clusteredKeys(1000)).dims, glm::ivec3(10, 10, 10));
}

TEST(SpatialHash, NoKeysGiveOneEmptySlot) {
  const SpatialHash h = buildSpatialHash({});
  EXPECT_EQ(h.slotCount(), 1u);
  EXPECT_EQ(h.offsetCount, 1);
  EXPECT_EQ(h.offsets.size(), 1u);
  EXPECT_TRUE(h.slots.empty());
}

TEST(SpatialHash, BuildsAreDeterministic) {
  const std::vector<glm::uvec3> keys = clusteredKeys(20000);
  const SpatialHash a = buildSpatialHash(keys), b = buildSpatialHash(keys);
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.offsetCount, b.offsetCount);
  EXPECT_EQ(a.attempts, b.attempts);
  EXPECT_EQ(a.salt, b.salt);
  EXPECT_TRUE(a.offsets == b.offsets);
  EXPECT_TRUE(a.slots == b.slots);
}

// The hash functions spelled out as bake/spatial_hash.h documents them (and the GLSL has them).
std::uint32_t mix(std::uint32_t x) {
  x = (x ^ (x >> 16)) * 0x7feb352du;
  x = (x ^ (x >> 15)) * 0x846ca68bu;
  return x ^ (x >> 16);
}

std::uint32_t documentedSlot(const SpatialHash& h, glm::uvec3 k) {
  const glm::uvec3 d(h.dims), r = k % d, q = k / d;
  const std::uint32_t x = mix(r.x + d.x * (r.y + d.y * r.z));
  const std::uint32_t quotient =
      h.salt == 0 ? q.x + 61 * q.y + 3721 * q.z : mix(q.x + mix(q.y + mix(q.z + h.salt)));
  const auto count = std::uint32_t(h.offsetCount);
  const std::uint32_t entry = (x % count + quotient % count) % count;
  const glm::uvec3 s = (k + glm::uvec3(h.offsets[entry])) % d;
  return s.x + d.x * (s.y + d.y * s.z);
}

// Pairs of keys with the same residue and the same linear quotient term (quotients differing
// by (61, -1, 0)): a 10x10x10 table of 1000 keys cannot separate them for any R.
std::vector<glm::uvec3> twinKeys() {
  std::vector<glm::uvec3> keys;
  for (std::uint32_t i = 0; i < 500; ++i) {
    const glm::uvec3 k(i % 10, 10 + i / 10 % 10, i / 100);
    keys.push_back(k);
    keys.push_back(k + glm::uvec3(610, 0, 0) - glm::uvec3(0, 10, 0));
  }
  return keys;
}

TEST(SpatialHash, KeysTheLinearTermCannotSeparateGetASalt) {
  const SpatialHash h = buildSpatialHash(twinKeys());
  EXPECT_EQ(h.dims, glm::ivec3(10, 10, 10));
  EXPECT_NE(h.salt, 0);
  expectPerfect(twinKeys(), "twins");
  // A table of 2 slots (1, 1, 2): both keys have residue 0 and quotient term 61.
  const SpatialHash pair = buildSpatialHash({{61, 0, 0}, {0, 1, 0}});
  EXPECT_EQ(pair.dims, glm::ivec3(1, 1, 2));
  EXPECT_NE(pair.salt, 0);
  expectPerfect({{61, 0, 0}, {0, 1, 0}}, "pair");
}

TEST(SpatialHash, SlotsFollowTheDocumentedFunctions) {
  for (const auto& keys : {scatteredKeys(1000), slabKeys(5000), twinKeys()}) {
    const SpatialHash h = buildSpatialHash(keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      ASSERT_EQ(documentedSlot(h, keys[i]), h.slots[i]) << "key " << i;
    }
  }
}

TEST(SpatialHash, TexelsHoldTheOffsetsAndTheSalt) {
  for (const auto& keys : {clusteredKeys(500), twinKeys()}) {
    const SpatialHash h = buildSpatialHash(keys);
    const std::vector<std::uint16_t> texels = spatialHashTexels(h);
    ASSERT_EQ(texels.size(), 4 * h.offsets.size());
    for (std::size_t e = 0; e < h.offsets.size(); ++e) {
      EXPECT_EQ(glm::u16vec3(texels[4 * e], texels[4 * e + 1], texels[4 * e + 2]), h.offsets[e]);
      EXPECT_EQ(texels[4 * e + 3], e == 0 ? h.salt : 0);
    }
  }
}

std::string buildError(const std::vector<glm::uvec3>& keys) {
  try {
    buildSpatialHash(keys);
  } catch (const BakeError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SpatialHash, RejectsKeysOutOfRangeAndEqualKeys) {
  EXPECT_EQ(buildError({{1, 2, 3}, {4, 2097152, 0}}),
            "spatial hash: key 1: expected components below 2097152, got (4, 2097152, 0)");
  EXPECT_EQ(buildError({{1, 2, 3}, {9, 9, 9}, {1, 2, 3}}),
            "spatial hash: keys 0 and 2 are both (1, 2, 3); expected distinct keys");
}

}  // namespace
}  // namespace manylight
