// Lightcuts against the reference method at 640×480 on the generated room scene (mixed
// point/spot/directional lights), in one run: render time, the speed-up, and light and node
// evaluations per covered pixel. Targets: at 65,536 lights lightcuts (ε = 0.02)
// ≥ 100× faster than the reference, and its time at 65,536 lights ≤ 3× its time at 1,024.
// Run: build/bin/manylight_lightcuts_bench   (most of the run is the 65,536-light reference
// frame)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "base/huge_pages.h"
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

const Scene& roomWith(int lights) {
  static std::map<int, Scene> scenes;
  auto it = scenes.find(lights);
  if (it == scenes.end()) {
    RoomOptions o;
    o.lightCount = lights;
    const auto path = std::filesystem::temp_directory_path() / "manylight-lightcuts-bench.glb";
    writeRoomScene(path.string(), o);
    it = scenes.emplace(lights, loadGltf(path.string())).first;
  }
  return it->second;
}

std::map<std::pair<Method, int>, double> gMilliseconds;  // median per method and light count

void renderTime(benchmark::State& state, Method method) {
  context();
  const int lights = int(state.range(0));
  const Scene& scene = roomWith(lights);
  const int w = 640, h = 480;
  double bakeMs = 0.0;
  const std::unique_ptr<Renderer> owned =
      prepareRenderer(scene, scene.lights, w, h, method, {}, {}, &bakeMs);
  Renderer& renderer = *owned;
  const View view = makeView(scene.cameras[0], w, h);
  FrameSettings settings;  // lightcuts defaults: ε = 0.02, node rule
  FrameStats stats;
  renderer.render(view, settings, &stats);  // warm-up: shader compile
  std::vector<double> times;
  for (auto _ : state) {
    renderer.render(view, settings, &stats);
    state.SetIterationTime(stats.renderMs / 1000.0);
    times.push_back(stats.renderMs);
  }
  std::sort(times.begin(), times.end());
  gMilliseconds[{method, lights}] = times[times.size() / 2];
  state.counters["lights"] = lights;
  if (method != Method::Reference) {
    state.counters["avg_cut"] = stats.cuts.averageCut;
    state.counters["light_evals_per_px"] = stats.cuts.lightEvaluations;
    state.counters["node_evals_per_px"] = stats.cuts.nodeEvaluations;
    state.counters["px_at_max_cut"] = double(stats.cuts.pixelsAtMaxCut);
    state.counters["bake_ms"] = bakeMs;
  } else {
    state.counters["light_evals_per_px"] = lights;
  }
}

BENCHMARK_CAPTURE(renderTime, lightcuts, Method::Lightcuts)
    ->Arg(1024)
    ->Arg(65536)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(renderTime, reference, Method::Reference)
    ->Arg(1024)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(renderTime, reference, Method::Reference)
    ->Arg(65536)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  manylight::restartWithHugePages(argv);  // as the command line does
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  auto ms = [](Method m, int n) {
    auto it = gMilliseconds.find({m, n});
    return it == gMilliseconds.end() ? 0.0 : it->second;
  };
  for (int n : {1024, 65536}) {
    const double ref = ms(Method::Reference, n), cut = ms(Method::Lightcuts, n);
    if (ref > 0.0 && cut > 0.0)
      std::printf("%d lights: lightcuts %.0f ms, reference %.0f ms, %.1fx faster\n", n, cut, ref,
                  ref / cut);
  }
  const double small = ms(Method::Lightcuts, 1024), large = ms(Method::Lightcuts, 65536);
  if (small > 0.0 && large > 0.0)
    std::printf("lightcuts 65,536 / 1,024 lights: %.2fx the time\n", large / small);
  return 0;
}
