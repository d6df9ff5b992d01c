// Loading a baked scene: 1,048,576 scattered lights (mixed point/spot/directional) with their
// packed light trees, read back from a baked file (bake/baked_file.h): the whole read, the
// checksum and every check of the format, nothing rebuilt. Target: ≤ 1 s.
// Run: build/bin/manylight_baked_bench
#include <benchmark/benchmark.h>

#include <filesystem>

#include "bake/baked_file.h"
#include "generators/scene_builder.h"

namespace {

using namespace manylight;

const std::string& bakedFile(int lights) {
  static std::string path;
  if (path.empty()) {
    Scene scene;
    scene.name = "generated";
    scene.lights = scatteredLights(lights, true, 11, {100.0f, 20.0f, 100.0f});
    path = (std::filesystem::temp_directory_path() / "manylight-baked-bench.mlbake").string();
    writeBakedScene(path, bakeScene(std::move(scene), TreeOptions{}));
  }
  return path;
}

void loadBaked(benchmark::State& state) {
  const std::string& path = bakedFile(int(state.range(0)));
  for (auto _ : state) {
    BakedScene b = readBakedScene(path);
    benchmark::DoNotOptimize(b.packed.words.data());
  }
  state.counters["bytes"] = double(std::filesystem::file_size(path));
  state.counters["lights"] = double(state.range(0));
}
BENCHMARK(loadBaked)->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
