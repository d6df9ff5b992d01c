// The manylight program's numeric options and the context's limits, as a user meets them:
// non-finite numbers, sizes past what the context renders, and the note before a slow
// reference render.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "generators/scene_builder.h"
#include "gl/limits.h"
#include "image/image.h"
#include "render/render_job.h"
#include "tests/cli_support.h"
#include "tests/gl_support.h"

namespace manylight::testing {
namespace {

// Every numeric option of every command, as "COMMAND ARGS|OPTION|VALUE" where X in VALUE is
// replaced by the number under test. Options holding integers refuse "nan" and "inf" as
// non-numbers; float options by the finiteness check; text options by their parsers.
struct NumericOption {
  const char* command;  // with the arguments the command needs to get as far as its options
  const char* option;
  const char* value;
};
constexpr const char* kRender = "render x.gltf -o OUT/y.png";
constexpr const char* kPlay = "play x.gltf -o OUT/f%04d.png";
constexpr const char* kBake = "bake x.gltf -o OUT/y.mlbake";
constexpr const char* kBench = "bench --csv OUT/b.csv";
const NumericOption kNumericOptions[] = {
    {kRender, "--exposure", "X"},
    {kRender, "--error", "X"},
    {kRender, "--ambient", "X,0,0"},
    {kRender, "--ambient", "0,X,0"},
    {kRender, "--ambient", "0,0,X"},
    {kRender, "--crease-angle", "X"},
    {kRender, "--size", "Xx16"},
    {kRender, "--size", "16xX"},
    {kRender, "--camera", "X"},
    {kRender, "--max-cut", "X"},
    {kRender, "--cut-tile", "X"},
    {kRender, "--light-budget", "X"},
    {kRender, "--max-file-bytes", "X"},
    {kRender, "--max-texture-size", "X"},
    {kRender, "--max-texture-pixels", "X"},
    {kRender, "--max-triangles", "X"},
    {"render x.gltf --out-dir OUT", "--shard", "X/2"},
    {"render x.gltf --out-dir OUT", "--shard", "0/X"},
    {kPlay, "--fps", "X"},
    {kPlay, "--orbit", "X"},
    {kPlay, "--exposure", "X"},
    {kPlay, "--error", "X"},
    {kPlay, "--frames", "X"},
    {kPlay, "--size", "Xx16"},
    {kPlay, "--camera", "X"},
    {kPlay, "--max-cut", "X"},
    {kPlay, "--cut-tile", "X"},
    {kPlay, "--crease-angle", "X"},
    {kPlay, "--light-budget", "X"},
    {kBake, "--crease-angle", "X"},
    {kBake, "--light-budget", "X"},
    {kBake, "--max-triangles", "X"},
    {kBench, "--reference-seconds", "X"},
    {kBench, "--errors", "0.01,X"},
    {kBench, "--counts", "64,X"},
    {kBench, "--repeats", "X"},
    {kBench, "--frames", "X"},
    {kBench, "--max-cut", "X"},
    {kBench, "--light-budget", "X"},
    {kBench, "--size", "16xX"},
    {"compare OUT/a.png OUT/b.png", "--max-abs", "X"},
    {"compare OUT/a.png OUT/b.png", "--max-fraction", "X"},
    {"fit-gamma --calibrate x.gltf", "--codes", "X..255"},
    {"fit-gamma --calibrate x.gltf", "--codes", "11..X"},
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at))
    text.replace(at, from.size(), to), at += to.size();
  return text;
}

TEST(CliOptions, NonFiniteNumbersAreRefusedNamingTheOption) {
  const std::string out = testFolder().string();
  for (const NumericOption& o : kNumericOptions) {
    for (const char* number : {"nan", "inf", "-inf", "NaN", "infinity"}) {
      const std::string args =
          replaced(o.command, "OUT", out) + " " + o.option + " " + replaced(o.value, "X", number);
      SCOPED_TRACE(args);
      const ProcessResult r = manylight(args);
      EXPECT_EQ(r.exitCode, 2) << r.err;
      EXPECT_EQ(r.err.rfind("manylight: " + std::string(o.option) + ": ", 0), 0u) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(fs::is_empty(testFolder())) << "an output was written";
    }
  }
}

TEST(CliOptions, FloatOptionsSayAFiniteNumberIsExpected) {
  // Options without a range: the finiteness check is all that stands between NaN and a
  // black image.
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string out = (testFolder() / "x.png").string();
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"render " + scene + " -o " + out + " --exposure nan",
       "manylight: --exposure: expected a finite number, got 'nan'\n"},
      {"render " + scene + " -o " + out + " --exposure -inf",
       "manylight: --exposure: expected a finite number, got '-inf'\n"},
      {"render " + scene + " -o " + out + " --error nan",
       "manylight: --error: expected a finite number, got 'nan'\n"},
      {"render " + scene + " -o " + out + " --ambient 0,inf,0",
       "manylight: --ambient: expected R,G,B, three finite numbers, got '0,inf,0'\n"},
      {"play " + scene + " -o " + out + " --orbit inf",
       "manylight: --orbit: expected a finite number, got 'inf'\n"},
      {"play " + scene + " -o " + out + " --fps nan",
       "manylight: --fps: expected a finite number, got 'nan'\n"},
      {"compare " + out + " " + out + " --max-fraction nan",
       "manylight: --max-fraction: expected a finite number, got 'nan'\n"},
      {"render " + scene + " -o " + out + " --indirect caches --rsm-least-share nan",
       "manylight: --rsm-least-share: expected a finite number, got 'nan'\n"},
      {"render " + scene + " -o " + out + " --indirect caches --rsm-least-share 2",
       "manylight: --rsm-least-share: Value 2 not in range 0.000000 to 1.000000\n"},
  };
  for (const Case& c : cases) {
    const ProcessResult r = manylight(c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args;
    EXPECT_EQ(r.err, c.message) << c.args;
  }
  const ProcessResult fine = manylight("render " + scene + " -o " + out +
                                       " --size 16x16 --exposure -1.5 --ambient 0.1,0,1e-3");
  EXPECT_EQ(fine.exitCode, 0) << fine.err;
}

// The largest side --size takes before asking the context (app/commands.h, kMaxSizeSide).
constexpr int kLargestSizeSide = 1 << 16;

TEST(CliOptions, SizesPastTheContextsLimitsAreRefusedBeforeRendering) {
  context();
  const int side = gl::renderSizeLimits().maxTextureSize + 1;
  if (side > kLargestSizeSide) GTEST_SKIP() << "the context renders sides of " << side - 1;
  const std::string size = std::to_string(side) + "x16";
  const std::string expected =
      "manylight: --size " + size + " " + gl::renderSizeExceeded(side, 16) + "\n";
  EXPECT_NE(expected.find("exceeds the context's GL_MAX_TEXTURE_SIZE"), std::string::npos);
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const fs::path dir = testFolder();
  const std::string commands[] = {
      "render " + scene + " -o " + (dir / "x.png").string(),
      "render " + scene + " --out-dir " + (dir / "thumbs").string(),
      "play " + scene + " -o " + (dir / "f%d.png").string() + " --frames 1",
      "bench --counts 64 --methods reference --repeats 1 --csv " + (dir / "b.csv").string(),
  };
  for (const std::string& command : commands) {
    const ProcessResult r = manylight(command + " --size " + size);
    EXPECT_EQ(r.exitCode, 1) << command;
    EXPECT_EQ(r.err, expected) << command;
    EXPECT_TRUE(fs::is_empty(dir)) << command << ": an output was written";
  }
}

// A scene whose camera looks away from its one box: every pixel is background, which the
// reference's lighting passes discard at once, so its render is fast whatever lights ×
// pixels.
std::string lookingAway() {
  GltfBuilder b;
  b.addBox({0, 0, 0}, {1, 1, 1}, b.addMaterial({}));
  b.addPerspectiveCamera({0, 0, -20}, {0, 0, -40}, 0.8f);
  const fs::path path = testFolder() / "away.glb";
  b.write(path.string());
  return path.string();
}

// `count` point lights as a light list (read about five times faster than glTF nodes).
std::string lightList(int count) {
  std::ostringstream csv;
  csv << "x,y,z,r,g,b,brightness\n";
  for (int i = 0; i < count; ++i)
    csv << i % 16 << "," << i / 16 % 16 << "," << i / 256 << ",255,200,100,1\n";
  return writeText("lights.csv", csv.str());
}

TEST(CliOptions, TheOctreeNamesLightsWhoseRangeHoldsTheWholeScene) {
  const std::string scene = lookingAway();
  const std::string lights = writeText(
      "huge.csv",
      "x,y,z,r,g,b,brightness,radius\n0,0,0,255,255,255,1,1000\n2,0,0,255,255,255,1,1000\n"
      "5,5,5,255,255,255,1,0.5\n");
  const std::string out = (testFolder() / "huge.png").string();
  const std::string stats = (testFolder() / "huge.json").string();
  const ProcessResult r = manylight("render " + scene + " --lights " + lights + " -o " + out +
                                    " --size 32x24 --method octree --stats " + stats);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.err, "manylight: " + scene +
                       ": warning: 2 ranged lights reach the whole scene (their range holds its "
                       "bounds), so the octree leaves them to the list every pixel evaluates: "
                       "light 0, 1\n");
  const nlohmann::json s = nlohmann::json::parse(readFile(stats));
  EXPECT_EQ(s["octree"]["whole_scene_lights"], 2);
  EXPECT_EQ(s["octree"]["global_lights"], 2);
  EXPECT_EQ(s["octree"]["unreached_lights"], 1);  // the third misses the box
}

// `--indirect` that adds nothing says why on stderr (`play`: in how many frames), and the
// frames are written all the same: no light of the sample scene sends all of the view's flux,
// and point lights cast none.
TEST(CliOptions, IndirectLightThatAddsNothingSaysWhy) {
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string out = (testFolder() / "none.png").string();
  const std::string render = "render " + scene + " -o " + out + " --size 32x24 --indirect ";
  const ProcessResult some = manylight(render + "exact");
  ASSERT_EQ(some.exitCode, 0) << some.err;
  EXPECT_EQ(some.err, "");
  const ProcessResult none = manylight(render + "caches --rsm-least-share 1");
  ASSERT_EQ(none.exitCode, 0) << none.err;
  EXPECT_EQ(none.err, "manylight: " + out +
                          ": --indirect caches: no spot or directional light sends 1 of the "
                          "view's flux (--rsm-least-share): no indirect light added\n");
  EXPECT_TRUE(fs::exists(out));
  const std::string frames = (testFolder() / "f%d.png").string();
  const ProcessResult played = manylight("play " + scene + " -o " + frames +
                                         " --size 32x24 --frames 2 --indirect exact "
                                         "--rsm-least-share 1");
  ASSERT_EQ(played.exitCode, 0) << played.err;
  EXPECT_EQ(played.err, "manylight: " + frames +
                            ": --indirect exact: no spot or directional light sends 1 of the "
                            "view's flux (--rsm-least-share): no indirect light added (2 of 2 "
                            "frames)\n");
  const std::string points =
      writeText("points.csv", "x,y,z,r,g,b,brightness\n0,0,-30,255,255,255,1\n");
  const ProcessResult pointOnly = manylight("render " + lookingAway() + " --lights " + points +
                                            " -o " + out + " --size 32x24 --indirect exact");
  ASSERT_EQ(pointOnly.exitCode, 0) << pointOnly.err;
  EXPECT_EQ(pointOnly.err, "manylight: " + out +
                               ": --indirect exact: the scene has no spot or directional light "
                               "to cast it: no indirect light added\n");
}

TEST(CliOptions, TheDefaultMethodIsChosenPerSceneAndSaysWhy) {
  // 65,536 lights without a range × 320×240 pixels = 5.0e9 light evaluations: lightcuts.
  const std::string scene = lookingAway();
  const std::string out = (testFolder() / "x.png").string();
  const std::string stats = (testFolder() / "x.json").string();
  const std::string render =
      "render " + scene + " --lights " + lightList(65536) + " -o " + out + " --stats " + stats;
  const ProcessResult bare = manylight(render + " --size 320x240 --verbose");
  ASSERT_EQ(bare.exitCode, 0) << bare.err;
  EXPECT_NE(bare.err.find("manylight: " + scene +
                          ": auto: lightcuts: 65536 lights, 65536 without a range: the octree "
                          "would evaluate those at every pixel; the reference would take up to "
                          "about 13 s, so lightcuts"),
            std::string::npos)
      << bare.err;
  const nlohmann::json s = nlohmann::json::parse(readFile(stats));
  EXPECT_EQ(s["method"], "lightcuts");
  EXPECT_NE(s["method_reason"].get<std::string>().find("65536 lights, 65536 without a range"),
            std::string::npos);
  // Asked for by name: nothing to say, no reason in the stats.
  const ProcessResult named = manylight(render + " --method reference --size 32x24");
  EXPECT_EQ(named.exitCode, 0) << named.err;
  EXPECT_EQ(named.err, "");
  EXPECT_FALSE(nlohmann::json::parse(readFile(stats)).contains("method_reason"));
}

// Pixels whose cut reached --max-cut before the rule held are named: a line on stderr with
// their count, the count in --stats, and where they are in --max-cut-mask's image.
TEST(CliOptions, PixelsAtTheMaximumCutAreCountedAndMasked) {
  RoomOptions room;
  room.lightCount = 4096;
  room.textured = false;
  const std::string scene = roomScene(room);
  const std::string out = (testFolder() / "total.png").string();
  const std::string mask = (testFolder() / "mask.png").string();
  const std::string stats = (testFolder() / "total.json").string();
  const ProcessResult r =
      manylight("render " + scene + " -o " + out + " --size 64x48 --method lightcuts " +
                "--cut-tile 1 --max-cut 16 --max-cut-mask " + mask + " --stats " + stats);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(readFile(stats));
  const long long atMax = s["pixels_at_max_cut"].get<long long>();
  ASSERT_GT(atMax, 0);
  EXPECT_EQ(r.err, "manylight: " + out + ": " + std::to_string(atMax) + " of " +
                       std::to_string(s["covered_pixels"].get<long long>()) +
                       " pixels reached the maximum cut (--max-cut 16; 8000 for cuts shared by "
                       "groups of pixels) before the error rule held: their error is not "
                       "bounded\n");
  const Image m = readImage(mask);
  ASSERT_EQ(m.width, 64);
  ASSERT_EQ(m.height, 48);
  long long white = 0;
  for (int y = 0; y < m.height; ++y) {
    for (int x = 0; x < m.width; ++x) {
      const float v = m.pixel(x, y)[0];
      EXPECT_TRUE(v == 0.0f || v == 1.0f) << "pixel " << x << ", " << y;
      white += v == 1.0f ? 1 : 0;
    }
  }
  EXPECT_EQ(white, atMax);
  // The default maximum: no pixel reaches it, the mask is black and nothing is said.
  const ProcessResult node = manylight("render " + scene + " -o " + out +
                                       " --size 64x48 --method lightcuts --max-cut-mask " + mask);
  ASSERT_EQ(node.exitCode, 0) << node.err;
  EXPECT_EQ(node.err, "");
  const Image black = readImage(mask);
  ASSERT_EQ(black.rgba.size(), std::size_t(64 * 48 * 4));
  for (std::size_t i = 0; i < black.rgba.size(); i += 4) ASSERT_EQ(black.rgba[i], 0.0f);
  // A batch has one mask path for many scenes: refused.
  const ProcessResult batch =
      manylight("render " + scene + " --out-dir " + (testFolder() / "batch").string() +
                " --max-cut-mask " + mask);
  EXPECT_EQ(batch.exitCode, 2);
  EXPECT_EQ(batch.err, "manylight: render: --max-cut-mask takes one scene (-o), not --out-dir\n");
  // The mask in place of the image: refused.
  const ProcessResult same = manylight("render " + scene + " -o " + out + " --max-cut-mask " + out);
  EXPECT_EQ(same.exitCode, 2);
  EXPECT_EQ(same.err, "manylight: render: --max-cut-mask names the output image " + out + "\n");
}

}  // namespace
}  // namespace manylight::testing
