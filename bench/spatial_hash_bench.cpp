// Perfect spatial hash build time (bake/spatial_hash.h) for octree-like key sets: the target
// is well under 1 s for 1,000,000 keys on one core. Counters: table slots per key, offset
// entries per key, constructions tried, offset table bytes (RGBA16UI texels, 8 per entry).
// Run: build/bin/manylight_spatial_hash_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <unordered_set>

#include "bake/spatial_hash.h"

namespace {

using namespace manylight;

// All cells of three slabs 8 cells thick, 64 cells apart, filled row by row.
std::vector<glm::uvec3> slabKeys(std::size_t n) {
  const auto side = std::uint32_t(std::ceil(std::sqrt(double(n) / 24.0)));
  std::vector<glm::uvec3> keys;
  for (std::uint32_t z = 0; keys.size() < n; ++z) {
    for (std::uint32_t y = 0; y < side && keys.size() < n; ++y) {
      for (std::uint32_t x = 0; x < side && keys.size() < n; ++x) {
        keys.push_back({x + 300, y + 700, (z / 8) * 64 + z % 8});
      }
    }
  }
  return keys;
}

// n distinct cells drawn uniformly from base + [0, extent)^3.
std::vector<glm::uvec3> randomKeys(std::size_t n, std::uint32_t extent, std::uint32_t base) {
  std::mt19937 random(17);
  std::unordered_set<std::uint64_t> seen;
  std::vector<glm::uvec3> keys;
  while (keys.size() < n) {
    const glm::uvec3 k(base + random() % extent, base + random() % extent,
                       base + random() % extent);
    if (seen.insert(k.x | std::uint64_t(k.y) << 21 | std::uint64_t(k.z) << 42).second) {
      keys.push_back(k);
    }
  }
  return keys;
}

enum class KeySet { kSlabs, kGrid200, kScattered };

std::vector<glm::uvec3> keySet(KeySet set, std::size_t n) {
  switch (set) {
    case KeySet::kSlabs:
      return slabKeys(n);
    case KeySet::kGrid200:  // a random subset of a 200^3 grid (or a denser one for more keys)
      return randomKeys(n, std::max(200u, std::uint32_t(std::cbrt(2.0 * double(n))) + 1), 4096);
    case KeySet::kScattered:  // anywhere in the 2^21 key domain
      break;
  }
  return randomKeys(n, kSpatialHashKeyLimit, 0);
}

void buildHash(benchmark::State& state, KeySet set) {
  const std::vector<glm::uvec3> keys = keySet(set, std::size_t(state.range(0)));
  SpatialHash h;
  for (auto _ : state) {
    h = buildSpatialHash(keys);
    benchmark::DoNotOptimize(h.slots.data());
  }
  const double n = double(keys.size());
  state.counters["keys"] = n;
  state.counters["slots_per_key"] = double(h.slotCount()) / n;
  state.counters["offsets_per_key"] = double(h.offsetCount) / n;
  state.counters["attempts"] = h.attempts;
  state.counters["offset_bytes"] = 8.0 * h.offsetCount;
}

BENCHMARK_CAPTURE(buildHash, Slabs, KeySet::kSlabs)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(buildHash, Grid200, KeySet::kGrid200)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(buildHash, Scattered, KeySet::kScattered)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
