// Throughput of the reference method: light evaluations per second at 640×480.
// Run: build/bin/manylight_bench  (evals_per_s = lights × covered pixels / render time)
#include <benchmark/benchmark.h>

#include <filesystem>

#include "generators/scene_builder.h"
#include "gl/context.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"

namespace {

using namespace manylight;

gl::Context& context() {
  static std::unique_ptr<gl::Context> ctx = gl::createContext(gl::Backend::Auto);
  return *ctx;
}

void referenceThroughput(benchmark::State& state, bool pointOnly, bool specular) {
  context();
  RoomOptions o;
  o.lightCount = int(state.range(0));
  o.mix = !pointOnly;
  o.specular = specular;
  const auto path = std::filesystem::temp_directory_path() / "manylight-bench-room.gltf";
  writeRoomScene(path.string(), o);
  const Scene scene = loadGltf(path.string());
  const int w = 640, h = 480;
  Renderer renderer(scene, scene.lights, w, h, Method::Reference);
  const View view = makeView(scene.cameras[0], w, h);
  // Warm-up (the driver compiles shaders on first use); count the covered pixels, since
  // background pixels evaluate no lights.
  const Image first = renderer.render(view, {});
  double covered = 0.0;
  for (std::size_t i = 3; i < first.rgba.size(); i += 4) covered += first.rgba[i] > 0.0f;
  double totalMs = 0.0;
  for (auto _ : state) {
    FrameStats stats;
    renderer.render(view, {}, &stats);
    state.SetIterationTime(stats.renderMs / 1000.0);
    totalMs += stats.renderMs;
  }
  const double evals = double(o.lightCount) * covered * state.iterations();
  state.counters["evals_per_s"] = benchmark::Counter(evals / (totalMs / 1000.0));
  state.counters["lights"] = double(o.lightCount);
  state.counters["covered"] = covered / (w * h);
}

void BM_ReferenceMixed(benchmark::State& s) { referenceThroughput(s, false, false); }
void BM_ReferencePoint(benchmark::State& s) { referenceThroughput(s, true, false); }
void BM_ReferenceMixedSpecular(benchmark::State& s) { referenceThroughput(s, false, true); }

BENCHMARK(BM_ReferenceMixed)
    ->Arg(1)
    ->Arg(512)
    ->Arg(4096)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK(BM_ReferencePoint)
    ->Arg(4096)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK(BM_ReferenceMixedSpecular)
    ->Arg(4096)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
