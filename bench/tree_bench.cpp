// Light tree build time (bake/light_tree.h): the target is ≤ 5 s for 1,048,576
// lights on the 2-core machine. Run: build/bin/manylight_tree_bench
#include <benchmark/benchmark.h>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "generators/scene_builder.h"

namespace {

using namespace manylight;

void buildTrees(benchmark::State& state, Split split, bool mixed) {
  const std::vector<Light> lights =
      scatteredLights(int(state.range(0)), mixed, 3, {100.0f, 10.0f, 100.0f});
  TreeOptions options;
  options.split = split;
  for (auto _ : state) {
    PackedTrees packed = packLightTrees(buildLightTrees(lights, options));
    benchmark::DoNotOptimize(packed.words.data());
  }
  state.counters["lights"] = double(lights.size());
}

// The packing alone (node colours encoded and measured), of trees built once.
void packTrees(benchmark::State& state) {
  const std::vector<Light> lights =
      scatteredLights(int(state.range(0)), true, 3, {100.0f, 10.0f, 100.0f});
  const std::vector<LightTree> trees = buildLightTrees(lights, TreeOptions{});
  for (auto _ : state) {
    PackedTrees packed = packLightTrees(trees);
    benchmark::DoNotOptimize(packed.words.data());
  }
  state.counters["lights"] = double(lights.size());
}

BENCHMARK(packTrees)->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(buildTrees, MetricPoint, Split::Metric, false)
    ->Arg(1 << 16)
    ->Arg(1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(buildTrees, MetricMixed, Split::Metric, true)
    ->Arg(1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(buildTrees, LongestAxisPoint, Split::LongestAxis, false)
    ->Arg(1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
