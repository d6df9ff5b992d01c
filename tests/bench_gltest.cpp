// The benchmark sweep and the stability suite on GL: the reference's row subset, the sweep's
// records against the total rule's guarantee, `manylight bench` and bench/report.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "generators/light_layouts.h"
#include "render/method_choice.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/cli_support.h"
#include "tests/gl_support.h"
#include "tools/sweep.h"

namespace manylight::testing {
namespace {

const Scene& room() {
  context();
  return untexturedRoom();
}

TEST(Bench, SweepReferenceRowSubsetLightsExactlyItsRows) {
  context();
  const int w = 40, h = 50;
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 300, 7);
  Renderer renderer(room(), lights, w, h, Method::Reference);
  const View view = makeView(room().cameras[0], w, h);
  FrameSettings all;
  all.lightsPerPass = 64;  // the same passes both ways, so the same float sums
  FrameSettings some = all;
  some.rowBandStride = 3;
  const Image full = renderer.render(view, all), part = renderer.render(view, some);
  const std::vector<bool> rows = rowsLit(h, 3);
  int lit = 0;
  for (int y = 0; y < h; ++y) {
    lit += rows[y];
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        if (rows[y])
          ASSERT_EQ(part.pixel(x, y)[c], full.pixel(x, y)[c]) << x << "," << y;
        else
          ASSERT_EQ(part.pixel(x, y)[c], 0.0f) << x << "," << y;  // no ambient, no emission
      }
    }
  }
  // Bands of 8 counted from the bottom row: image rows 42..49 (band 0), 18..25 (band 3)
  // and 0..1 (band 6, cut short by the top edge).
  EXPECT_EQ(lit, 18);
  EXPECT_TRUE(rows[49] && rows[42] && !rows[41] && rows[25] && rows[18] && !rows[17] && rows[1] &&
              rows[0] && !rows[2]);
}

// One timed frame a variant at 48x36.
SweepSettings smallSweep(const std::vector<SweepVariant>& variants) {
  SweepSettings s;
  s.width = 48;
  s.height = 36;
  s.repeats = 1;
  s.variants = variants;
  return s;
}

TEST(Bench, SweepRecordsHoldTheTotalRuleAndTheReferenceIsExact) {
  context();
  SweepSettings s =
      smallSweep(expandVariants({Method::Reference, Method::Lightcuts, Method::LightcutsDistance},
                                {ErrorMode::Total}, {0.02f}));
  s.maxCut = 8000;
  Sweep sweep(room(), s);
  EXPECT_GT(sweep.floorMs(), 0.0);
  const auto records = sweep.run(layoutCase(LightLayout::Clustered, 500), [](auto&) {});
  ASSERT_EQ(records.size(), 3u);
  for (const RunRecord& r : records) {
    EXPECT_EQ(r.failure, "") << r.variant.label();
    EXPECT_EQ(r.caseName, "clustered-500");
    EXPECT_GT(r.renderMs, 0.0);
    EXPECT_GT(r.errors.pixels, 500);
    EXPECT_EQ(r.rowBandStride, 1);
  }
  EXPECT_EQ(records[0].variant.label(), "reference");
  EXPECT_EQ(records[0].errors.maxRelative, 0.0);
  EXPECT_EQ(records[0].ratioToReference, 1.0);
  EXPECT_EQ(records[0].lightEvaluationsPerPixel, 500.0);
  EXPECT_EQ(records[1].variant.label(), "lightcuts-total-0.02");
  EXPECT_EQ(records[1].pixelsAtMaxCut, 0);
  // The guarantee, with the float slack of lightcuts_gltest.cpp.
  EXPECT_LE(records[1].errors.maxRelative, 0.02 + 1e-4);
  EXPECT_GT(records[1].averageCut, 1.0);
  EXPECT_NEAR(records[1].ratioToReference, records[1].renderMs / records[0].renderMs, 1e-9);
  EXPECT_EQ(records[2].variant.label(), "lightcuts-distance");
}

TEST(Bench, ACaseWithItsOwnErrorRunsEachRuleOnceAtIt) {
  context();
  const SweepSettings s = smallSweep(expandVariants(
      {Method::Reference, Method::Lightcuts}, {ErrorMode::Node, ErrorMode::Total}, {0.02f, 0.05f}));
  const std::vector<SweepCase> suite = stabilityCases();
  const auto fine = std::find_if(suite.begin(), suite.end(), [](const SweepCase& c) {
    return c.name == "clustered-fine-16384";
  });
  ASSERT_NE(fine, suite.end());
  EXPECT_EQ(fine->layout, LightLayout::Clustered);
  EXPECT_EQ(fine->error, 0.005f);
  SweepCase c = *fine;
  c.lights = 400;  // the case's ε on fewer lights, at a size a test affords
  const auto records = Sweep(room(), s).run(c, [](auto&) {});
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].variant.label(), "reference");
  EXPECT_EQ(records[1].variant.label(), "lightcuts-node-0.005");
  EXPECT_EQ(records[2].variant.label(), "lightcuts-total-0.005");
  for (const RunRecord& r : records) EXPECT_EQ(r.failure, "") << r.variant.label();
  EXPECT_EQ(records[2].pixelsAtMaxCut, 0);
  // The total rule's guarantee at the case's ε, with the float slack of lightcuts_gltest.cpp.
  EXPECT_LE(records[2].errors.maxRelative, 0.005 + 1e-4);
}

TEST(Bench, SweepSlowReferencesLightARowSubsetAndSaySo) {
  context();
  SweepSettings s;
  s.width = 48;
  s.height = 64;
  s.repeats = 1;
  s.referenceSeconds = 1e-6;  // every reference is "too slow"
  s.variants = expandVariants({Method::Reference, Method::Lightcuts}, {ErrorMode::Node}, {0.02f});
  Sweep sweep(room(), s);
  const auto records = sweep.run(layoutCase(LightLayout::Uniform, 200), [](auto&) {});
  ASSERT_EQ(records.size(), 2u);
  // The largest stride: one band of eight rows in 64.
  EXPECT_EQ(records[0].rowBandStride, 8);
  EXPECT_EQ(records[1].rowBandStride, 8);
  EXPECT_LE(records[1].errors.pixels, 48 * 8);
  EXPECT_GT(records[1].errors.pixels, 0);
}

TEST(Bench, CliBenchWritesEveryRunAsCsvAndJson) {
  const fs::path dir = testFolder();
  const ProcessResult r = manylight(
      "bench --layouts uniform,street --counts 8,40 --methods reference,lightcuts --modes node "
      "--errors 0.05,0.1 --size 32x24 --repeats 1 --csv " +
      (dir / "s.csv").string() + " --json " + (dir / "s.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("manylight: bench: 4 cases x 3 methods"), std::string::npos) << r.err;
  const std::string csv = readFile(dir / "s.csv");
  EXPECT_EQ(csv.rfind("case,layout,lights,method,mode,error,max_cut,", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 * 3);
  EXPECT_NE(csv.find("\nstreet-40,street,40,lightcuts,node,0.1,2000,32,24,1,"), std::string::npos)
      << csv;
  const auto json = nlohmann::json::parse(readFile(dir / "s.json"));
  EXPECT_EQ(json["runs"].size(), 12u);
  EXPECT_GT(json["floor_ms"].get<double>(), 0.0);
  EXPECT_EQ(json["runs"][0]["label"], "reference");
  EXPECT_EQ(json["runs"][0]["max_rel_error"], 0.0);

  // Resuming keeps the finished cases and runs only the new count.
  const ProcessResult more = manylight(
      "bench --layouts uniform,street --counts 8,40,41 --methods reference,lightcuts --modes "
      "node --errors 0.05,0.1 --size 32x24 --repeats 1 --resume --csv " +
      (dir / "s.csv").string() + " --json " + (dir / "s.json").string());
  ASSERT_EQ(more.exitCode, 0) << more.err;
  const std::string resumed = readFile(dir / "s.csv");
  EXPECT_EQ(resumed.substr(0, csv.size()), csv);
  EXPECT_EQ(std::count(resumed.begin(), resumed.end(), '\n'), 1 + 6 * 3);
  EXPECT_EQ(nlohmann::json::parse(readFile(dir / "s.json"))["runs"].size(), 18u);

  // Results of another build (or GL renderer) are not resumed: they would mix two programs'
  // numbers.
  auto older = nlohmann::json::parse(readFile(dir / "s.json"));
  EXPECT_EQ(older["build"].get<std::string>().size(), 16u);
  older["build"] = "0123456789abcdef";
  std::ofstream(dir / "s.json") << older.dump();
  const ProcessResult refused = manylight(
      "bench --layouts uniform --counts 8 --methods reference --size 32x24 --repeats 1 --resume "
      "--json " +
      (dir / "s.json").string());
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_EQ(refused.err, "manylight: " + (dir / "s.json").string() +
                             ": cannot resume: it was measured with another build; remove it or "
                             "run without --resume\n");
}

TEST(Bench, CliBenchRefusesBadRequestsInOneLine) {
  const std::string out = " --json " + (testFolder() / "x.json").string();
  struct Case {
    std::string args, message;
    int exitCode;
  };
  const Case cases[] = {
      {"bench --size 8x8", "manylight: bench: give --csv FILE, --json FILE or both\n", 2},
      {"bench --layouts spiral" + out,
       "manylight: unknown light layout 'spiral' (choose from uniform, clustered, street, mixed, "
       "coincident, two-groups, wide-intensities, bright-among-dim, far, spots-away, on-surfaces, "
       "eight-bit-colours, uniform-ranged, street-ranged)\n",
       1},
      {"bench --counts 2000000" + out,
       "manylight: uniform-2000000: 2000000 lights exceed the light budget of 1048576\n", 1},
      {"bench --counts 12,x" + out, "manylight: --counts: 'x' is not a number in 1..67108864\n", 2},
      {"bench --methods reference,hashed" + out,
       "manylight: unknown method 'hashed', expected reference, lightcuts, lightcuts-distance, "
       "octree or auto\n",
       1},
      {"bench --suite stability --cases count-4" + out, "", 2},
  };
  for (const Case& c : cases) {
    const ProcessResult r = manylight(c.args);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.args << "\n" << r.err;
    if (!c.message.empty()) {
      EXPECT_EQ(r.err, c.message) << c.args;
    }
    EXPECT_FALSE(fs::exists(testFolder() / "x.json")) << c.args;
  }
}

TEST(Bench, CliStabilitySuiteAndReportWriteThePages) {
  const fs::path dir = testFolder();
  const fs::path results = dir / "results", docs = dir / "docs";
  ProcessResult r = manylight(
      "bench --layouts mixed --counts 3,50 --size 32x24 --repeats 1 "
      "--errors 0.02 --csv " +
      (results / "sweep.csv").string() + " --json " + (results / "sweep.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = manylight(
      "bench --suite stability --cases count-3,spots-away-16384 --size 32x24 "
      "--frames 3 --json " +
      (results / "stability.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stability = nlohmann::json::parse(readFile(results / "stability.json"));
  EXPECT_EQ(stability["runs"].size(), 2u * 4u);  // reference, node, total, distance
  ASSERT_EQ(stability["temporal"].size(), 3u);
  EXPECT_EQ(stability["temporal"][0]["frames"], 3);
  ASSERT_EQ(shell("python3 " MANYLIGHT_SOURCE_DIR "/bench/report.py " + results.string() + " " +
                  docs.string()),
            0);
  for (const char* png : {"frontier-mixed.png", "scaling-mixed.png"})
    EXPECT_GT(fs::file_size(docs / "charts" / png), 1000u) << png;
  const std::string page = readFile(docs / "stability.md");
  EXPECT_NE(page.find("| count-3 | "), std::string::npos) << page;
  EXPECT_NE(page.find("### spots-away-16384"), std::string::npos) << page;
  EXPECT_NE(page.find("## Temporal stability"), std::string::npos) << page;
  EXPECT_NE(readFile(docs / "benchmarks.md").find("## The frontier at 50 lights"),
            std::string::npos);
}

TEST(Bench, ReferenceEstimateFollowsTheMeasuredThroughput) {
  // Lights × every pixel (covered or not) over kReferenceEvaluationsPerSecond:
  // 65,536 × 640 × 480 / 4e8 = 50.3 s.
  EXPECT_NEAR(referenceSecondsEstimate(65536, 640, 480), 50.3, 0.1);
  EXPECT_NEAR(referenceSecondsEstimate(1048576, 640, 480), 805.3, 0.1);
  EXPECT_EQ(referenceSecondsEstimate(0, 640, 480), 0.0);
}

TEST(Bench, AutoChoosesByTheCostModel) {
  const Scene& scene = room();
  // 1,000 lights × 256×256 = 6.6e7 light evaluations: the reference.
  std::vector<Light> few(1000);
  MethodChoice c = chooseMethod(scene, few, 256, 256, {});
  EXPECT_EQ(c.method, Method::Reference);
  EXPECT_EQ(c.reason,
            "1000 lights × 256×256 pixels: the reference is exact and takes up to about 0.16 s");
  // 65,536 lights without a range at 640×480: lightcuts.
  std::vector<Light> unranged(65536);
  c = chooseMethod(scene, unranged, 640, 480, {});
  EXPECT_EQ(c.method, Method::Lightcuts);
  EXPECT_EQ(c.reason,
            "65536 lights, 65536 without a range: the octree would evaluate those at every "
            "pixel; the reference would take up to about 50 s, so lightcuts (approximate, "
            "within its documented error at --error)");
  EXPECT_FALSE(c.octree);
  // The same with short ranges: the octree, and the octree it built to decide.
  const std::vector<Light> ranged = layoutLights(LightLayout::UniformRanged, 65536, 7);
  c = chooseMethod(scene, ranged, 640, 480, {});
  EXPECT_EQ(c.method, Method::Octree) << c.reason;
  ASSERT_TRUE(c.octree);
  EXPECT_EQ(c.reason.find("65536 lights: the octree is exact and its lists hold about "), 0u)
      << c.reason;
}

}  // namespace
}  // namespace manylight::testing
