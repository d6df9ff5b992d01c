// Light tree build time (bake/light_tree.h): the target is ≤ 5 s for 1,048,576
// lights on the 2-core machine. Run: build/bin/manylight_tree_bench
#include <random>

#include <benchmark/benchmark.h>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"

namespace {

using namespace manylight;

std::vector<Light> randomLights(int count, bool mixed) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Light> lights(count);
  for (int i = 0; i < count; ++i) {
    Light& l = lights[i];
    l.type = mixed ? LightType(i % 3) : LightType::Point;
    l.position = {100.0f * u(rng), 10.0f * u(rng), 100.0f * u(rng)};
    l.direction = glm::normalize(glm::vec3(u(rng) - 0.5f, -1.0f, u(rng) - 0.5f));
    l.colour = {u(rng), u(rng), u(rng)};
    l.intensity = 1.0f + 9.0f * u(rng);
    l.range = i % 2 ? 0.0f : 5.0f + 10.0f * u(rng);
  }
  return lights;
}

void buildTrees(benchmark::State& state, Split split, bool mixed) {
  const std::vector<Light> lights = randomLights(int(state.range(0)), mixed);
  TreeOptions options;
  options.split = split;
  for (auto _ : state) {
    PackedTrees packed = packLightTrees(buildLightTrees(lights, options));
    benchmark::DoNotOptimize(packed.texels.data());
  }
  state.counters["lights"] = double(lights.size());
}

BENCHMARK_CAPTURE(buildTrees, MetricPoint, Split::Metric, false)
    ->Arg(1 << 16)->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(buildTrees, MetricMixed, Split::Metric, true)
    ->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(buildTrees, LongestAxisPoint, Split::LongestAxis, false)
    ->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
