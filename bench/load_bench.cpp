// Loading glTF scenes through scene/gltf_loader.h: the generated room with 1,048,576 and
// 262,144 mixed lights (as manylight_make_scene writes it), as a GLB and as a .gltf, and the
// sample-sized room with 8 lights. Everything loadGltf does is timed: reading the file,
// simdjson over the nodes and lights, tinygltf over the rest, the meshes, and placing every
// light. Run: build/bin/manylight_load_bench
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>

#include "generators/scene_builder.h"
#include "scene/gltf_loader.h"

namespace {

using namespace manylight;

// The room with `lights` lights, written once per process as `ext` (".glb" or ".gltf").
const std::string& roomFile(int lights, const std::string& ext) {
  static std::map<std::pair<int, std::string>, std::string> files;
  std::string& path = files[{lights, ext}];
  if (path.empty()) {
    RoomOptions o;
    o.lightCount = lights;
    path = (std::filesystem::temp_directory_path() /
            ("manylight-load-bench-" + std::to_string(lights) + ext))
               .string();
    writeRoomScene(path, o);
  }
  return path;
}

void load(benchmark::State& state, const std::string& ext) {
  const std::string& path = roomFile(int(state.range(0)), ext);
  for (auto _ : state) {
    Scene s = loadGltf(path);
    benchmark::DoNotOptimize(s.lights.data());
  }
  state.counters["bytes"] = double(std::filesystem::file_size(path));
  state.counters["lights"] = double(state.range(0));
}

void loadGlb(benchmark::State& state) { load(state, ".glb"); }
void loadGltfText(benchmark::State& state) { load(state, ".gltf"); }

BENCHMARK(loadGlb)
    ->Arg(8)
    ->Arg(1 << 18)
    ->Arg(1 << 20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(loadGltfText)->Arg(8)->Arg(1 << 18)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
