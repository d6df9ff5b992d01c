// The CPU half of shared tile cuts (cuts/tile_cuts.h): finding one cut per screen square
// of a 640×480 G-buffer, at 1,024 and 65,536 uniform lights, node and total rules, on one
// thread and on all. The G-buffer is synthetic (a floor seen from above, a wall on the
// right) so that no GL is needed. Run: build/bin/manylight_tile_cuts_bench
#include <benchmark/benchmark.h>

#include <cstring>
#include <map>
#include <thread>

#include "bake/light_tree.h"
#include "bake/light_tree_pack.h"
#include "cuts/tile_cuts.h"
#include "generators/light_layouts.h"

namespace {

using namespace manylight;

constexpr int kWidth = 640, kHeight = 480;

struct Frame {
  std::vector<float> position, normal, specular;
  Frame()
      : position(kWidth * kHeight * 4),
        normal(kWidth * kHeight * 4),
        specular(kWidth * kHeight * 4) {
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t i = (std::size_t(y) * kWidth + x) * 4;
        const float u = float(x) / kWidth, v = float(y) / kHeight;
        glm::vec3 p{-3.0f + 7.5f * u, 0.0f, -3.0f + 6.0f * v}, n{0.0f, 1.0f, 0.0f};
        if (u > 0.8f) {
          p = {3.0f, 15.0f * (u - 0.8f), -3.0f + 6.0f * v};
          n = {-1.0f, 0.0f, 0.0f};
        }
        std::memcpy(&position[i], &p, 12);
        std::memcpy(&normal[i], &n, 12);
        normal[i + 3] = 1.0f;
      }
    }
  }
};

const TileCutter& cutter(int lights) {
  static std::map<int, std::unique_ptr<TileCutter>> cutters;
  auto& c = cutters[lights];
  if (!c) {
    const std::vector<Light> all = layoutLights(LightLayout::Uniform, lights, 7);
    c = std::make_unique<TileCutter>(packLightTrees(buildLightTrees(all)), all);
  }
  return *c;
}

void cutFrame(benchmark::State& state) {
  static const Frame frame;
  const GBufferPixels px{kWidth, kHeight, frame.position.data(), frame.normal.data(),
                         frame.specular.data()};
  const TileCutter& c = cutter(int(state.range(0)));
  const CutRule rule{0.02f, state.range(1) == 1, 1000};
  const int threads =
      state.range(2) == 0 ? int(std::max(1u, std::thread::hardware_concurrency())) : 1;
  TileCuts cuts;
  for (auto _ : state) {
    cuts = c.cut(px, 16, rule, threads);
    benchmark::DoNotOptimize(cuts.texels.head.data());
  }
  state.counters["threads"] = threads;
  state.counters["bounds"] = double(cuts.boundEvaluations());
  state.counters["entry_texels"] = double(cuts.texels.texels() - 2 * std::size_t(cuts.sharedCuts));
  state.counters["shared_cuts"] = cuts.sharedCuts;
  state.counters["per_pixel_groups"] = cuts.perPixelGroups;
  state.counters["surface_splits"] = cuts.surfaceSplits;
}

// Arguments: lights, rule (0 node, 1 total), threads (0 all, 1 one).
BENCHMARK(cutFrame)
    ->Args({1024, 0, 0})
    ->Args({65536, 0, 0})
    ->Args({65536, 0, 1})
    ->Args({65536, 1, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
