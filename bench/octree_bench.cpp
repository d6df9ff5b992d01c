// Light octree build time (bake/light_octree.h) over the generated room's geometry, for the
// ranged layouts of generators/light_layouts.h: the target is ≤ 2 s for 1,048,576 lights on
// the 2-core machine. Run: build/bin/manylight_octree_bench
#include <benchmark/benchmark.h>

#include <cstdio>

#include "bake/light_octree.h"
#include "generators/light_layouts.h"
#include "generators/scene_builder.h"
#include "scene/gltf_loader.h"

namespace {

using namespace manylight;

const Scene& room() {
  static const Scene scene = [] {
    const std::string path = "/tmp/manylight_octree_bench_room.glb";
    RoomOptions options;
    options.lightCount = 1;
    writeRoomScene(path, options);
    Scene s = loadGltf(path);
    std::remove(path.c_str());
    return s;
  }();
  return scene;
}

void buildOctree(benchmark::State& state, LightLayout layout) {
  const std::vector<Light> lights = layoutLights(layout, int(state.range(0)), 7);
  const Scene& scene = room();
  LightOctree octree;
  OctreeOptions options;
  options.leafEdge = float(state.range(1)) * octreeLeafEdge(lights);
  for (auto _ : state) {
    octree = buildLightOctree(lights, scene, options);
    benchmark::DoNotOptimize(octree.indices.data());
  }
  state.counters["lights"] = double(lights.size());
  state.counters["levels"] = octree.levels;
  state.counters["nodes"] = double(octree.nodeCount());
  state.counters["indices"] = double(octree.indices.size());
  state.counters["max_list"] = octree.maxLeafCount;
}

BENCHMARK_CAPTURE(buildOctree, UniformRanged, LightLayout::UniformRanged)
    ->Args({1 << 16, 1})
    ->Args({1 << 20, 1})
    ->Args({1 << 20, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(buildOctree, StreetRanged, LightLayout::StreetRanged)
    ->Args({1 << 16, 1})
    ->Args({1 << 20, 1})
    ->Args({1 << 20, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
