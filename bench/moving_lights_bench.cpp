// Moving lights: 1% of 65,536 ranged lights (generators' uniform-ranged layout in the room)
// moved per frame. Targets: the octree's update costs ≤ 10% of a rebuild (MoveOnePercent
// against Rebuild), and a playback frame at 640×360 (moving, updating, uploading and
// rendering) ≥ 10 fps (PlaybackFrame). Lightcuts' trees refitted and packed against baked
// anew: TreesRefitOnePercent against TreesRebuild.
// Run: build/bin/manylight_moving_lights_bench
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "bake/octree_update.h"
#include "bake/tree_update.h"
#include "generators/light_layouts.h"
#include "generators/scene_builder.h"
#include "gl/context.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"

namespace {

using namespace manylight;

constexpr int kLights = 65536;

const Scene& room() {
  static const Scene scene = [] {
    RoomOptions o;
    o.lightCount = 1;
    const auto path = std::filesystem::temp_directory_path() / "manylight-moving-bench.glb";
    writeRoomScene(path.string(), o);
    Scene s = loadGltf(path.string());
    s.lights = layoutLights(LightLayout::UniformRanged, kLights, 7);
    return s;
  }();
  return scene;
}

// Moves 1% of the lights by up to 5 cm along each axis; returns the indices moved.
std::vector<int> moveSome(std::vector<Light>& lights, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, int(lights.size()) - 1);
  std::uniform_real_distribution<float> step(-0.05f, 0.05f);
  std::vector<int> changed;
  for (std::size_t k = 0; k < lights.size() / 100; ++k) changed.push_back(pick(rng));
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  for (int i : changed)
    lights[std::size_t(i)].position += glm::vec3(step(rng), step(rng), step(rng));
  return changed;
}

void Rebuild(benchmark::State& state) {
  const Scene& scene = room();
  for (auto _ : state) {
    DynamicOctree octree(scene.lights, scene);
    benchmark::DoNotOptimize(octree.packed().indices.data());
  }
}

void MoveOnePercent(benchmark::State& state) {
  const Scene& scene = room();
  std::vector<Light> lights = scene.lights;
  DynamicOctree octree(lights, scene);
  std::mt19937 rng(1);
  for (auto _ : state) {
    state.PauseTiming();
    const std::vector<int> changed = moveSome(lights, rng);
    state.ResumeTiming();
    if (!octree.update(lights, changed)) state.SkipWithError("update refused");
  }
  state.counters["entries_moved"] = double(octree.entriesMoved());
}

// Lightcuts' trees: baked anew against refitted in place and packed, for the same moves.
void TreesRebuild(benchmark::State& state) {
  const Scene& scene = room();
  for (auto _ : state) benchmark::DoNotOptimize(bakeLightTrees(scene.lights).words.data());
}

void TreesRefitOnePercent(benchmark::State& state) {
  const Scene& scene = room();
  std::vector<Light> lights = scene.lights;
  DynamicTrees trees(lights, {});
  std::mt19937 rng(1);
  for (auto _ : state) {
    state.PauseTiming();
    const std::vector<int> changed = moveSome(lights, rng);
    state.ResumeTiming();
    if (!trees.update(lights, changed)) state.SkipWithError("refit refused");
    benchmark::DoNotOptimize(trees.packed().words.data());
  }
}

void PlaybackFrame(benchmark::State& state) {
  static std::unique_ptr<gl::Context> context = gl::createContext(gl::Backend::Auto);
  const Scene& scene = room();
  const int w = 640, h = 360;
  std::vector<Light> lights = scene.lights;
  const std::unique_ptr<Renderer> renderer = prepareRenderer(scene, lights, w, h, Method::Octree);
  const View view = makeView(scene.cameras[0], w, h);
  FrameSettings settings;
  std::mt19937 rng(1);
  renderer->moveLights(lights, moveSome(lights, rng), {});  // the first move builds the octree
  renderer->render(view, settings);
  for (auto _ : state) {
    renderer->moveLights(lights, moveSome(lights, rng), {});
    renderer->render(view, settings);
  }
  state.counters["fps"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(Rebuild)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(MoveOnePercent)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(TreesRebuild)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(TreesRefitOnePercent)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(PlaybackFrame)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(120);

}  // namespace

BENCHMARK_MAIN();
