// Perfect spatial hashing with 3-D offset vectors (Lefebvre & Hoppe 2006); the hash functions
// are described in bake/spatial_hash.h.
#include "bake/spatial_hash.h"

#include <algorithm>
#include <string>

#include "bake/colour_fit.h"  // BakeError

namespace manylight {

namespace {

constexpr std::uint32_t kQuotientStrideY = 61, kQuotientStrideZ = 61 * 61;
constexpr std::uint32_t kNone = 0xffffffffu;
// Offset entries per key of the first construction, and the growth after a group could not
// be placed; a residue clash (two keys that always collide sharing an entry) grows R by 1/16.
constexpr double kInitialEntriesPerKey = 0.25, kGrowthAfterStuck = 1.3;
// Failed constructions per table size before the next larger table (within 1.1 n); failed
// constructions before every further one takes a new salt; R's limit in entries per key.
constexpr int kAttemptsPerTable = 4, kAttemptsBeforeSalts = 12;
constexpr double kMostEntriesPerKey = 4.0;

// "lowbias32" (Chris Wellons' hash prospector): a full-avalanche 32-bit integer finaliser.
std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// splitmix64, for the order in which candidate slots are tried.
struct Random {
  std::uint64_t state = 0x5eed5a17ca5eull;
  std::uint32_t below(std::uint32_t n) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return std::uint32_t(((z >> 32) * n) >> 32);
  }
};

std::uint32_t linearIndex(glm::uvec3 s, glm::uvec3 d) { return s.x + d.x * (s.y + d.y * s.z); }

// The two terms of h1 that do not depend on R: mix of the residue index, quotient index.
struct EntryTerms {
  std::uint32_t mixed = 0, quotient = 0;
};

// The quotient term: linear for salt 0, else a salted hash (never equal for two quotients
// that differ in one component only).
std::uint32_t quotientTerm(glm::uvec3 q, std::uint32_t salt) {
  if (salt == 0) return q.x + kQuotientStrideY * q.y + kQuotientStrideZ * q.z;
  return mix32(q.x + mix32(q.y + mix32(q.z + salt)));
}

EntryTerms entryTerms(glm::uvec3 key, glm::uvec3 d, std::uint32_t salt) {
  return {mix32(linearIndex(key % d, d)), quotientTerm(key / d, salt)};
}

std::uint32_t entryOf(EntryTerms t, std::uint32_t r) { return (t.mixed % r + t.quotient % r) % r; }

std::uint64_t volume(glm::ivec3 d) { return std::uint64_t(d.x) * std::uint64_t(d.y) * d.z; }

// Table extents a <= b <= c with a*b*c in [n, n + n/10] and c <= 65536 (offsets are 16-bit);
// near-cubic ones (c <= 2a) by increasing product, or where there are none (small n) all, by
// increasing c/a. For each (a, b) only the smallest c, so there are O(n^(2/3)) of them.
std::vector<glm::ivec3> tableCandidates(std::uint64_t n) {
  const std::uint64_t limit = n + n / 10;
  std::vector<glm::ivec3> all, cubic;
  for (std::uint64_t a = 1; a * a * a <= limit; ++a) {
    for (std::uint64_t b = a; a * b * b <= limit; ++b) {
      const std::uint64_t c = std::max(b, (n + a * b - 1) / (a * b));
      if (a * b * c > limit || c > 65536) continue;
      const glm::ivec3 d(static_cast<int>(a), static_cast<int>(b), static_cast<int>(c));
      (c <= 2 * a ? cubic : all).push_back(d);
    }
  }
  if (!cubic.empty()) {
    std::sort(cubic.begin(), cubic.end(),
              [&](glm::ivec3 p, glm::ivec3 q) { return volume(p) < volume(q); });
    return cubic;
  }
  std::sort(all.begin(), all.end(), [&](glm::ivec3 p, glm::ivec3 q) {
    return std::uint64_t(p.z) * q.x < std::uint64_t(q.z) * p.x;
  });
  return all;
}

// The keys grouped by offset entry: members[start[e] .. start[e + 1]) are entry e's keys.
struct Groups {
  std::vector<std::uint32_t> start, members;
};

Groups groupKeys(const std::vector<EntryTerms>& terms, std::uint32_t r,
                 std::vector<std::uint32_t>& entry) {
  Groups g;
  g.start.assign(r + 1, 0);
  for (std::size_t i = 0; i < terms.size(); ++i) {
    entry[i] = entryOf(terms[i], r);
    ++g.start[entry[i] + 1];
  }
  for (std::uint32_t e = 0; e < r; ++e) g.start[e + 1] += g.start[e];
  g.members.resize(terms.size());
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < terms.size(); ++i) g.members[fill[entry[i]]++] = std::uint32_t(i);
  return g;
}

std::string keyText(glm::uvec3 k) {
  return "(" + std::to_string(k.x) + ", " + std::to_string(k.y) + ", " + std::to_string(k.z) + ")";
}

// Two keys of one group with the same residue collide for every offset: a clash. It is exact
// when their quotient terms are equal too, so that no R can separate them.
enum class Clash { kNone, kModR, kExact };

// Whether two keys of one group have the same residue. Equal keys always do, so every clash
// is checked for them. Throws BakeError on equal keys.
Clash residueClash(const Groups& g, const std::vector<std::uint32_t>& residue,
                   const std::vector<std::uint32_t>& entry, const std::vector<EntryTerms>& terms,
                   const std::vector<glm::uvec3>& keys, std::size_t slots) {
  std::vector<std::uint32_t> seenBy(slots, kNone);  // a key with that residue
  Clash clash = Clash::kNone;
  for (std::uint32_t i : g.members) {
    std::uint32_t& seen = seenBy[residue[i]];
    if (seen != kNone && entry[seen] == entry[i]) {
      if (keys[seen] == keys[i]) {
        throw BakeError("spatial hash: keys " + std::to_string(seen) + " and " + std::to_string(i) +
                        " are both " + keyText(keys[i]) + "; expected distinct keys");
      }
      if (clash == Clash::kNone) clash = Clash::kModR;
      if (terms[seen].quotient == terms[i].quotient) clash = Clash::kExact;
    }
    seen = i;
  }
  return clash;
}

// Entries with keys, largest group first (counting sort; ties in entry order).
std::vector<std::uint32_t> entriesBySize(const Groups& g) {
  const std::uint32_t r = std::uint32_t(g.start.size() - 1);
  std::uint32_t largest = 0;
  for (std::uint32_t e = 0; e < r; ++e) largest = std::max(largest, g.start[e + 1] - g.start[e]);
  std::vector<std::uint32_t> first(largest + 2, 0);
  for (std::uint32_t e = 0; e < r; ++e) ++first[largest - (g.start[e + 1] - g.start[e]) + 1];
  for (std::uint32_t s = 0; s <= largest; ++s) first[s + 1] += first[s];
  const std::uint32_t withKeys = first[largest];  // the empty entries come last
  std::vector<std::uint32_t> order(r);
  for (std::uint32_t e = 0; e < r; ++e) order[first[largest - (g.start[e + 1] - g.start[e])]++] = e;
  order.resize(withKeys);
  return order;
}

// What placing one group needs: the table, a bit per slot (1: taken; 4 million slots take
// 512 KiB, so the random probes mostly hit the cache), and the residues of the group.
struct Placement {
  Placement(glm::uvec3 d, std::uint32_t slotCount)
      : dims(d), used((slotCount + 63) / 64, 0), slots(slotCount), freeCount(slotCount) {}
  bool isUsed(std::uint32_t s) const { return (used[s >> 6] >> (s & 63)) & 1; }
  void take(std::uint32_t s) { used[s >> 6] |= std::uint64_t(1) << (s & 63); }

  glm::uvec3 dims;
  std::vector<std::uint64_t> used;
  std::uint32_t slots, freeCount;
  std::uint32_t firstFree = 0;  // once single keys (placed last) begin: no free slot before it
  Random random;
  std::vector<glm::uvec3> group;
};

glm::uvec3 slotCoord(std::uint32_t s, glm::uvec3 d) {
  const std::uint32_t row = s / d.x;
  return {s - row * d.x, row % d.y, row / d.y};
}

// (residue + offset) mod d for residue, offset < d.
std::uint32_t slotOf(glm::uvec3 residue, glm::uvec3 offset, glm::uvec3 d) {
  const glm::uvec3 s = residue + offset;
  return linearIndex(glm::mix(s, s - d, glm::greaterThanEqual(s, d)), d);
}

// The offset taking residue r to slot coordinate c: (c - r) mod d, for c, r < d.
glm::uvec3 offsetTo(glm::uvec3 c, glm::uvec3 r, glm::uvec3 d) {
  return glm::mix(c + d - r, c - r, glm::greaterThanEqual(c, r));
}

// A slot and its coordinate, stepped through the table in slot order (wrapping), so a scan
// needs no division.
struct SlotCursor {
  std::uint32_t index;
  glm::uvec3 coord;
  void advance(glm::uvec3 d) {
    ++index;
    if (++coord.x < d.x) return;
    coord.x = 0;
    if (++coord.y < d.y) return;
    coord.y = 0;
    if (++coord.z < d.z) return;
    coord.z = 0;
    index = 0;
  }
};

// Whether every key of the group but the first lands on a free slot under `offset`.
bool othersFit(const Placement& p, glm::uvec3 offset) {
  for (std::size_t i = 1; i < p.group.size(); ++i) {
    if (p.isUsed(slotOf(p.group[i], offset, p.dims))) return false;
  }
  return true;
}

// Tries the first key on every free slot, from a random slot on in slot order (a sequential
// scan of the bits: cheap even when few slots are free); marks the group's slots taken. Single
// keys, placed last, take the first free slot.
bool placeGroup(Placement& p, const glm::u16vec3* residues, std::uint32_t size,
                glm::uvec3& offset) {
  if (p.freeCount < size) return false;
  p.group.assign(residues, residues + size);
  const glm::uvec3 d = p.dims;
  const std::uint32_t count = p.slots;
  const std::uint32_t start = size == 1 ? p.firstFree : p.random.below(count);
  SlotCursor at{start, slotCoord(start, d)};
  for (std::uint32_t i = 0; i < count; ++i, at.advance(d)) {
    if (p.isUsed(at.index)) continue;
    offset = offsetTo(at.coord, p.group[0], d);
    if (!othersFit(p, offset)) continue;
    for (glm::uvec3 r : p.group) p.take(slotOf(r, offset, d));
    p.freeCount -= size;
    if (size == 1) p.firstFree = at.index;
    return true;
  }
  return false;
}

enum class Outcome { kBuilt, kClash, kExactClash, kStuck };

// One construction for h.dims and h.offsetCount; fills h.offsets and h.slots on success.
Outcome construct(const std::vector<glm::uvec3>& keys, SpatialHash& h) {
  const glm::uvec3 d(h.dims);
  const std::uint32_t r = std::uint32_t(h.offsetCount);
  std::vector<EntryTerms> terms(keys.size());
  std::vector<std::uint32_t> residue(keys.size()), entry(keys.size());
  std::vector<glm::u16vec3> residue3(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    terms[i] = entryTerms(keys[i], d, h.salt);
    residue3[i] = glm::u16vec3(keys[i] % d);
    residue[i] = linearIndex(keys[i] % d, d);
  }
  const Groups groups = groupKeys(terms, r, entry);
  const Clash clash = residueClash(groups, residue, entry, terms, keys, h.slotCount());
  if (clash != Clash::kNone) return clash == Clash::kExact ? Outcome::kExactClash : Outcome::kClash;
  std::vector<glm::u16vec3> grouped(keys.size());  // residues in group order
  for (std::size_t i = 0; i < keys.size(); ++i) grouped[i] = residue3[groups.members[i]];
  Placement p(d, std::uint32_t(h.slotCount()));
  h.offsets.assign(r, glm::u16vec3(0));
  for (std::uint32_t e : entriesBySize(groups)) {
    glm::uvec3 offset;
    const glm::u16vec3* residues = grouped.data() + groups.start[e];
    if (!placeGroup(p, residues, groups.start[e + 1] - groups.start[e], offset)) {
      return Outcome::kStuck;
    }
    h.offsets[e] = glm::u16vec3(offset);
  }
  h.slots.resize(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    h.slots[i] = slotOf(residue3[i], glm::uvec3(h.offsets[entry[i]]), d);
  }
  return Outcome::kBuilt;
}

// The next table of `candidates` after `at` at least 2% larger, or `at` if there is none.
std::size_t largerTable(const std::vector<glm::ivec3>& candidates, std::size_t at) {
  const std::uint64_t wanted = volume(candidates[at]) + (volume(candidates[at]) + 49) / 50;
  for (std::size_t i = at + 1; i < candidates.size(); ++i) {
    if (volume(candidates[i]) >= wanted) return i;
  }
  return at;
}

void checkKeyRange(const std::vector<glm::uvec3>& keys) {
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const glm::uvec3 k = keys[i];
    if (std::max(k.x, std::max(k.y, k.z)) >= kSpatialHashKeyLimit) {
      throw BakeError("spatial hash: key " + std::to_string(i) + ": expected components below " +
                      std::to_string(kSpatialHashKeyLimit) + ", got " + keyText(k));
    }
  }
}

}  // namespace

std::size_t SpatialHash::slotCount() const { return std::size_t(volume(dims)); }

std::uint32_t spatialHashEntry(const SpatialHash& h, glm::uvec3 key) {
  return entryOf(entryTerms(key, glm::uvec3(h.dims), h.salt), std::uint32_t(h.offsetCount));
}

std::uint32_t hashSlot(const SpatialHash& h, glm::uvec3 key) {
  const glm::uvec3 d(h.dims);
  return linearIndex((key + glm::uvec3(h.offsets[spatialHashEntry(h, key)])) % d, d);
}

// Past kAttemptsPerTable failures on a table the next larger one is used while there is one.
// R grows (up to 4 n + 16), so groups shrink and the chance of success rises. An exact clash
// (no R separates two keys) and every attempt past kAttemptsBeforeSalts take a new salt,
// which makes each attempt an independent trial: the loop ends with probability 1.
SpatialHash buildSpatialHash(const std::vector<glm::uvec3>& keys) {
  SpatialHash h;
  h.offsets.assign(1, glm::u16vec3(0));
  if (keys.empty()) return h;
  checkKeyRange(keys);
  const std::vector<glm::ivec3> tables = tableCandidates(keys.size());
  std::size_t table = 0;
  double entries = std::max(1.0, kInitialEntriesPerKey * double(keys.size()));
  const double limit = kMostEntriesPerKey * double(keys.size()) + 16.0;
  for (int attempt = 1;; ++attempt) {
    h.dims = tables[table];
    h.offsetCount = int(entries);
    const Outcome outcome = construct(keys, h);
    if (outcome == Outcome::kBuilt) {
      h.attempts = attempt;
      return h;
    }
    const double grown =
        outcome == Outcome::kClash ? entries * (1.0 + 1.0 / 16.0) : entries * kGrowthAfterStuck;
    entries = std::min(std::max(grown, entries + 1.0), limit);
    if (outcome == Outcome::kExactClash || attempt >= kAttemptsBeforeSalts) {
      h.salt = std::uint16_t(h.salt == 0xffff ? 1 : h.salt + 1);
    }
    if (attempt % kAttemptsPerTable == 0) table = largerTable(tables, table);
  }
}

std::vector<std::uint16_t> spatialHashTexels(const SpatialHash& h) {
  std::vector<std::uint16_t> texels(4 * h.offsets.size(), 0);
  if (!texels.empty()) texels[3] = h.salt;
  for (std::size_t e = 0; e < h.offsets.size(); ++e) {
    for (int c = 0; c < 3; ++c) texels[4 * e + c] = h.offsets[e][c];
  }
  return texels;
}

}  // namespace manylight
