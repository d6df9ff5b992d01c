// The manylight subcommands beyond a single render, as a user runs them: fit-gamma, light
// lists, compare, batches, bake, play; and inputs that must never block.
#include <sys/stat.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "image/image.h"
#include "tests/cli_support.h"

namespace manylight::testing {
namespace {

TEST(CliTools, FitGammaPrintsTheUe4Fit) {
  const std::string pairs = writeText(
      "ue4.csv", "in,out\n255,5000\n216,3470\n171,2076\n123,1005\n85,445\n76,349\n59,200\n");
  const ProcessResult r = manylight("fit-gamma " + pairs);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NEAR(printed(r.out, "gamma"), 2.1996, 0.0005);
  EXPECT_NEAR(printed(r.out, "A"), 0.025430, 0.000005);
  EXPECT_NEAR(printed(r.out, "log10(A)"), -1.5947, 0.0001);
  EXPECT_GT(printed(r.out, "R^2"), 0.9999);
  EXPECT_NEAR(printed(r.out, "worst relative residual"), 0.0023, 0.0001);
  const std::string bad = writeText("one.csv", "in,out\n255,5000\n255,4000\n");
  const ProcessResult e = manylight("fit-gamma " + bad);
  EXPECT_EQ(e.exitCode, 1);
  EXPECT_EQ(e.err, "manylight: " + bad + ": a power-law fit needs at least two different inputs\n");
}

TEST(CliTools, CalibrationMeasuresTheExactSrgbCurve) {
  // Probes of grey 8-bit light colours on the reference path: the renderer decodes them with
  // the exact sRGB curve, so the fit is the best power law for that curve over codes 11–255
  // (computed independently in double precision: γ = 1.965171) and strays from it by up
  // to 11 codes. A renderer that decoded with a 2.2 power would give γ = 2.2.
  const ProcessResult r =
      manylight("fit-gamma --calibrate " + std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(printed(r.out, "pairs"), 245);
  EXPECT_NEAR(printed(r.out, "gamma"), 1.965171, 1e-4);
  EXPECT_NE(r.out.find("largest difference from the sRGB curve = 11 codes"), std::string::npos)
      << r.out;
}

TEST(CliTools, LightListsAddToTheScenesLights) {
  RoomOptions o;
  o.lightCount = 3;
  const std::string scene = roomScene(o);
  std::string csv = "x,y,z,r,g,b,brightness,radius\n";
  for (int i = 0; i < 40; ++i) {
    csv += std::to_string(-4 + i % 8) + ",2," + std::to_string(-2 + i / 8) + "," +
           std::to_string(i * 6) + ",76,216,3,6\n";
  }
  const std::string list = writeText("list.csv", csv);
  const fs::path dir = testFolder();
  for (const char* method : {"reference", "lightcuts"}) {
    const ProcessResult r =
        manylight("render " + scene + " --lights " + list + " -o " + (dir / "l.png").string() +
                  " --size 64x48 --method " + method + " --stats " + (dir / "s.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto stats = nlohmann::json::parse(readFile(dir / "s.json"));
    EXPECT_EQ(stats["lights"], 43);
    if (std::string(method) == "lightcuts") {
      EXPECT_EQ(stats["node_colour"]["coding"], "rgb9e5");
      EXPECT_EQ(stats["node_colour"]["bytes_per_node"], 40);
      EXPECT_LT(stats["node_colour"]["slack"].get<double>(), 0.0021);
    }
  }
  const std::string bad = writeText("bad.csv", "x,y,z,r,g,b,brightness\n1,2,3,4,5,6\n");
  const fs::path out = dir / "bad.png";
  const ProcessResult r = manylight("render " + scene + " --lights " + bad + " -o " + out.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + bad + ":2: expected 7 fields, got 6\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliTools, CompareAssertsARenderAgainstAStoredImage) {
  const fs::path dir = testFolder();
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string(),
                    small = (dir / "small.png").string();
  const std::string linear = " --tone-map none --exposure ";
  ASSERT_EQ(manylight("render " + scene + " -o " + a + " --size 64x48" + linear + "0").exitCode, 0);
  ASSERT_EQ(manylight("render " + scene + " -o " + b + " --size 64x48" + linear + "0.05").exitCode,
            0);
  ASSERT_EQ(manylight("render " + scene + " -o " + small + " --size 32x48" + linear + "0").exitCode,
            0);

  ProcessResult r = manylight("compare " + a + " " + a);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find(": match: 0 of 12288 values"), std::string::npos) << r.out;

  // A 3.5% brighter image: up to 4 codes (0.0157) apart.
  r = manylight("compare " + a + " " + b);
  EXPECT_EQ(r.exitCode, 4);
  EXPECT_NE(r.out.find(": differ: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max 0.0156863"), std::string::npos) << r.out;
  const fs::path diff = dir / "b.diff.png";
  ASSERT_TRUE(fs::exists(diff)) << "the difference image is written on failure";
  const Image d = readImage(diff.string());
  EXPECT_EQ(d.width, 64);
  fs::remove(diff);

  EXPECT_EQ(manylight("compare " + a + " " + b + " --max-abs 0.016").exitCode, 0);
  // Or allow the differing values as a share: below it fails, above it passes.
  EXPECT_EQ(
      manylight("compare " + a + " " + b + " --max-fraction 0.1 --diff " + (dir / "d.png").string())
          .exitCode,
      4);
  EXPECT_TRUE(fs::exists(dir / "d.png"));
  EXPECT_EQ(manylight("compare " + a + " " + b + " --max-fraction 0.5").exitCode, 0);
  EXPECT_FALSE(fs::exists(diff)) << "no difference image when they match";

  r = manylight("compare " + a + " " + small);
  EXPECT_EQ(r.exitCode, 4);
  EXPECT_NE(r.out.find("differ: 64x48 with 4 channels against 32x48 with 4"), std::string::npos)
      << r.out;
  const std::string missing = (dir / "missing.png").string();
  r = manylight("compare " + a + " " + missing);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err.rfind("manylight: " + missing + ": cannot read image: ", 0), 0u) << r.err;
}

// The relative test: the second image is the reference, its background (alpha 0) is left
// out, and the chosen percentile of the pixels' relative errors must stay within the limit.
TEST(CliTools, CompareRelativeErrorsAgainstAReference) {
  const fs::path dir = testFolder();
  Image ref;
  ref.width = 4;
  ref.height = 1;
  ref.rgba.assign(16, 1.0f);
  ref.pixel(3, 0)[3] = 0.0f;  // background
  Image img = ref;
  img.pixel(1, 0)[0] = 1.0078125f;  // 2⁻⁷ off (exact in binary, as printed)
  img.pixel(2, 0)[2] = 0.96875f;    // 2⁻⁵ off
  img.pixel(3, 0)[1] = 50.0f;       // never compared
  const std::string a = (dir / "rel_a.exr").string(), b = (dir / "rel_b.exr").string();
  writeImage(img, a);
  writeImage(ref, b);
  const std::string pair = a + " " + b + ": ";
  ProcessResult r = manylight("compare " + a + " " + b + " --max-relative 0.05");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out, pair +
                       "match: relative error against the second, at percentile 100: 0.03125 "
                       "(limit 0.05); max 0.03125 at pixel (2, 0); 3 pixels compared\n");
  r = manylight("compare " + a + " " + b + " --max-relative 0.02");
  EXPECT_EQ(r.exitCode, 4);
  const fs::path diff = dir / "rel_b.diff.png";
  EXPECT_EQ(r.out, pair +
                       "differ: relative error against the second, at percentile 100: 0.03125 "
                       "(limit 0.02); max 0.03125 at pixel (2, 0); 3 pixels compared; "
                       "difference: " +
                       diff.string() + "\n");
  // The difference: relative error / (2 · limit) as grey, the background black.
  const Image d = readImage(diff.string());
  ASSERT_EQ(d.width, 4);
  EXPECT_EQ(d.pixel(0, 0)[0], 0.0f);
  EXPECT_NEAR(d.pixel(1, 0)[0], 50.0f / 255.0f, 1e-6);   // 0.195 → code 50
  EXPECT_NEAR(d.pixel(2, 0)[0], 199.0f / 255.0f, 1e-6);  // 0.781 → code 199
  EXPECT_EQ(d.pixel(3, 0)[0], 0.0f);
  // The median of the three is the pixel 2⁻⁷ off.
  r = manylight("compare " + a + " " + b + " --max-relative 0.02 --percentile 50");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("at percentile 50: 0.0078125 (limit 0.02)"), std::string::npos) << r.out;
  // Another size differs, as value by value.
  Image wide = ref;
  wide.width = 2;
  wide.height = 2;
  const std::string c = (dir / "rel_c.exr").string();
  writeImage(wide, c);
  r = manylight("compare " + a + " " + c + " --max-relative 0.05");
  EXPECT_EQ(r.exitCode, 4);
  EXPECT_EQ(r.out, a + " " + c + ": differ: 4x1 with 4 channels against 2x2 with 4\n");
  r = manylight("compare " + a + " " + b + " --percentile 50");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--percentile requires --max-relative"), std::string::npos) << r.err;
}

// libpng prints "libpng error: ..." lines of its own for a corrupt PNG before OpenImageIO
// reports the error (one line before a texture's error, three before compare's). Each
// error stays one line, the program's own.
TEST(CliTools, ACorruptPngGivesOneLineOfError) {
  const fs::path dir = testFolder();
  const std::string png = (dir / "bad.png").string(), out = (dir / "out.png").string();
  std::ofstream(png, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) << "this is no PNG";
  const std::string scene =
      writeText("bad.gltf", R"({"asset": {"version": "2.0"}, "images": [{"uri": "bad.png"}]})");
  const std::string why = "PNG read error: [20]is[20]: invalid chunk type\n";
  ProcessResult r = manylight("render " + scene + " -o " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + scene + ": image 0: cannot decode image: " + why);
  EXPECT_FALSE(fs::exists(out));
  r = manylight("compare " + png + " " + png);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + png + ": cannot read image: Invalid image file \"" + png +
                       "\": " + why);
}

TEST(CliTools, BatchesRenderEverySceneInOneProcess) {
  const fs::path dir = testFolder();
  std::vector<std::string> scenes;
  for (int i = 0; i < 4; ++i) {
    RoomOptions o;
    o.lightCount = 2 + i;
    o.seed = std::uint32_t(i + 1);
    o.specular = i == 2;  // another shader variant mid-batch
    scenes.push_back(roomScene(o, "room" + std::to_string(i) + ".gltf"));
  }
  const std::string bad = writeText("broken.gltf", R"({"asset": {"version": "1.0"}})");
  std::string list = scenes[0] + " " + bad;
  for (int i = 1; i < 4; ++i) list += " " + scenes[i];
  const fs::path out = dir / "thumbs";
  const ProcessResult r = manylight("render " + list + " --out-dir " + out.string() +
                                    " --size 48x32 --stats " + (dir / "batch.json").string());
  EXPECT_EQ(r.exitCode, 1) << "a failed scene makes the batch fail, at the end";
  EXPECT_NE(
      r.err.find("manylight: " + bad + ": asset.version '1.0' is not supported, expected 2.x\n"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("manylight: rendered 4 of 5 scenes into " + out.string() + ", 1 failed"),
            std::string::npos)
      << r.err;
  const auto stats = nlohmann::json::parse(readFile(dir / "batch.json"));
  EXPECT_EQ(stats["rendered"], 4);
  EXPECT_EQ(stats["failed"], 1);
  EXPECT_EQ(stats["scenes"][1]["error"],
            bad + ": asset.version '1.0' is not supported, expected 2.x");
  // Each thumbnail is the image a process of its own renders, bit for bit.
  for (int i = 0; i < 4; ++i) {
    const fs::path single = dir / ("single" + std::to_string(i) + ".png");
    ASSERT_EQ(
        manylight("render " + scenes[i] + " -o " + single.string() + " --size 48x32").exitCode, 0);
    EXPECT_EQ(readFile(out / ("room" + std::to_string(i) + ".png")), readFile(single)) << i;
  }
  EXPECT_FALSE(fs::exists(out / "broken.png"));

  // Shards: every N-th scene from I, so N machines share a batch.
  const fs::path sharded = dir / "shard";
  const std::string good = scenes[0] + " " + scenes[1] + " " + scenes[2] + " " + scenes[3];
  ASSERT_EQ(manylight("render " + good + " --out-dir " + sharded.string() +
                      " --shard 1/2 --size 16x16 --format exr")
                .exitCode,
            0);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(sharded))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"room1.exr", "room3.exr"}));

  EXPECT_EQ(
      manylight("render " + list + " --out-dir " + sharded.string() + " --shard 2/2").exitCode, 2);
  EXPECT_EQ(manylight("render " + scenes[0] + " " + scenes[1] + " -o " + (dir / "x.png").string())
                .exitCode,
            2);
  const ProcessResult twice =
      manylight("render " + scenes[0] + " " + scenes[0] + " --out-dir " + sharded.string());
  EXPECT_EQ(twice.exitCode, 1);
  EXPECT_EQ(twice.err, "manylight: " + scenes[0] + ": would write " +
                           (sharded / "room0.png").string() + ", as " + scenes[0] +
                           " does; give scenes distinct names\n");
}

TEST(CliTools, BakedScenesRenderAsTheirSources) {
  RoomOptions o;
  o.lightCount = 200;
  const std::string scene = roomScene(o);
  const fs::path dir = testFolder();
  const std::string list =
      writeText("extra.csv", "x,y,z,r,g,b,brightness\n0,2,0,255,76,216,2\n1,2,1,10,200,30,2\n");
  const std::string baked = (dir / "room.mlbake").string();
  ProcessResult r = manylight("bake " + scene + " --lights " + list + " -o " + baked + " --stats " +
                              (dir / "bake.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(readFile(dir / "bake.json"))["lights"], 202);
  for (const char* method : {"reference", "lightcuts", "lightcuts-distance"}) {
    SCOPED_TRACE(method);
    const std::string args = std::string(" --size 64x48 --method ") + method;
    const fs::path fromScene = dir / "scene.png", fromBake = dir / "bake.png";
    ASSERT_EQ(
        manylight("render " + scene + " --lights " + list + " -o " + fromScene.string() + args)
            .exitCode,
        0);
    r = manylight("render " + baked + " -o " + fromBake.string() + args + " --stats " +
                  (dir / "s.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readFile(fromBake), readFile(fromScene))
        << "a baked scene renders bit for bit as its source";
    const auto stats = nlohmann::json::parse(readFile(dir / "s.json"));
    EXPECT_EQ(stats["lights"], 202);
    if (std::string(method) != "reference") {
      EXPECT_EQ(stats["baked_trees"], true);
    }
  }
  r = manylight("render " + baked + " --lights " + list + " -o " + (dir / "x.png").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + baked +
                       ": a baked scene's lights are baked in; bake it again with --lights\n");
  r = manylight("render " + baked + " --tree-split longest-axis --method lightcuts -o " +
                (dir / "x.png").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + baked +
                       ": baked with other --tree-split or --node-colour settings; bake it again "
                       "to change them\n");
  r = manylight("render " + baked + " --light-budget 100 -o " + (dir / "x.png").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + baked +
                       ": 202 lights exceed the light budget of 100 (--light-budget)\n");
  // A damaged bake: one line, nothing written.
  std::string bytes = readFile(baked);
  bytes[bytes.size() / 2] ^= 1;
  const std::string damaged = writeText("damaged.mlbake", "");
  std::ofstream(damaged, std::ios::binary) << bytes;
  r = manylight("render " + damaged + " -o " + (dir / "y.png").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_EQ(r.err, "manylight: " + damaged + ": checksum mismatch: the file is damaged\n");
  EXPECT_FALSE(fs::exists(dir / "y.png"));
  EXPECT_EQ(manylight("bake " + scene + " -o " + (dir / "room.bin").string()).exitCode, 2);
}

TEST(CliTools, PlaybackOrbitsTheCameraFrameByFrame) {
  const fs::path dir = testFolder();
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string frames = (dir / "frames" / "f%03d.png").string();
  ProcessResult r = manylight(
      "play " + scene + " -o " + frames +
      " --frames 4 --orbit 20 --size 48x32 --tone-map none --exposure 0 --method lightcuts"
      " --stats " +
      (dir / "play.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stats = nlohmann::json::parse(readFile(dir / "play.json"));
  EXPECT_EQ(stats["frames"], 4);
  EXPECT_EQ(stats["frame_render_ms"].size(), 4u);
  ASSERT_EQ(stats["frame_cut_ms"].size(), 4u);  // lightcuts with shared cuts
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_GT(stats["frame_cut_ms"][i].get<double>(), 0.0);
    EXPECT_LT(stats["frame_cut_ms"][i].get<double>(), stats["frame_render_ms"][i].get<double>());
  }
  EXPECT_GT(stats["render_fps"].get<double>(), 0.0);
  // Cuts are kept per cell of the scene from frame to frame: turning 20° in all, later frames
  // keep most of theirs (31 to 38 of 43 to 45 here).
  ASSERT_EQ(stats["frame_cuts_kept"].size(), 4u);
  EXPECT_EQ(stats["frame_cuts_kept"][0], 0);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_GT(stats["frame_cuts_kept"][i].get<int>(), stats["frame_cuts_made"][i].get<int>());
  }
  // With --fresh-cuts, frame 0 is the still render of the same camera, bit for bit (its cuts
  // are the squares' too); later frames have turned. The kept cuts' frame 0 differs from it
  // within the rule: by at most a code here.
  const fs::path still = dir / "still.png";
  ASSERT_EQ(manylight("render " + scene + " -o " + still.string() +
                      " --size 48x32 --method lightcuts --tone-map none --exposure 0")
                .exitCode,
            0);
  const std::string fresh = (dir / "fresh" / "f%03d.png").string();
  ASSERT_EQ(manylight("play " + scene + " -o " + fresh +
                      " --frames 4 --orbit 20 --size 48x32 --fresh-cuts --tone-map none "
                      "--exposure 0 --method lightcuts")
                .exitCode,
            0);
  EXPECT_EQ(readFile(dir / "fresh" / "f000.png"), readFile(still));
  EXPECT_NE(readFile(dir / "fresh" / "f002.png"), readFile(still));
  EXPECT_EQ(manylight("compare " + (dir / "frames" / "f000.png").string() + " " + still.string() +
                      " --max-abs 0.004")
                .exitCode,
            0);
  EXPECT_TRUE(fs::exists(dir / "frames" / "f003.png"));
  EXPECT_FALSE(fs::exists(dir / "frames" / "f004.png"));

  // Raw frames on stdout: 4 × 48 × 32 RGBA8, the first equal to the PNG's codes.
  const fs::path raw = dir / "frames.rgba";
  ASSERT_EQ(shell(std::string(MANYLIGHT_BIN) + " play " + scene +
                  " -o - --frames 4 --orbit 20 --size 48x32 --tone-map none --exposure 0 "
                  "--method lightcuts > " +
                  raw.string()),
            0);
  const std::string bytes = readFile(raw);
  ASSERT_EQ(bytes.size(), 4u * 48 * 32 * 4);
  const Image first = readImage((dir / "frames" / "f000.png").string());
  int off = 0;
  for (std::size_t i = 0; i < 48 * 32 * 4; ++i) {
    off += std::uint8_t(bytes[i]) != int(std::lround(first.rgba[i] * 255.0f));
  }
  EXPECT_EQ(off, 0);
}

TEST(CliTools, PlaybackStopsCleanly) {
  const fs::path dir = testFolder();
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  // A consumer that stops reading ends the playback cleanly, without hanging.
  EXPECT_EQ(shell(std::string(MANYLIGHT_BIN) + " play " + scene +
                  " -o - --frames 100000 --size 48x32 2>/dev/null | head -c 100 > /dev/null; exit "
                  "${PIPESTATUS[0]}"),
            0);
  // So does Ctrl-C: every frame written is whole, and no temporary file is left.
  const fs::path stopped = dir / "stopped";
  EXPECT_EQ(
      shell("timeout --preserve-status -s INT 3 " + std::string(MANYLIGHT_BIN) + " play " + scene +
            " -o " + (stopped / "%04d.png").string() + " --frames 100000 --size 48x32 2>/dev/null"),
      130);
  int written = 0;
  for (const auto& e : fs::directory_iterator(stopped)) {
    ++written;
    EXPECT_EQ(e.path().extension(), ".png") << e.path();
    EXPECT_EQ(e.path().filename().string().front() == '.', false)
        << "temporary file left: " << e.path();
    EXPECT_EQ(readImage(e.path().string()).width, 48);
  }
  EXPECT_GT(written, 0);

  EXPECT_EQ(manylight("play " + scene + " -o " + (dir / "nopattern.png").string()).exitCode, 2);
}

TEST(CliTools, PlaybackFollowsTheCameraAnimation) {
  // Keys at 0, 1 and 2 s; at 2 frames per second that is frames 0..4, the last on the last key.
  const std::string scene = animatedScene("animated");
  const fs::path dir = testFolder();
  const ProcessResult r =
      manylight("play " + scene + " -o " + (dir / "a%d.png").string() +
                " --fps 2 --size 32x24 --method reference --stats " + (dir / "p.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stats = nlohmann::json::parse(readFile(dir / "p.json"));
  EXPECT_EQ(stats["frames"], 5);
  EXPECT_EQ(stats["camera_animation"], true);
  EXPECT_TRUE(fs::exists(dir / "a4.png"));
  EXPECT_FALSE(fs::exists(dir / "a5.png"));
}

TEST(CliTools, FifosAreRefusedWithoutBlocking) {
  // Opening a FIFO for reading blocks until a writer comes; every input must be checked first.
  const fs::path fifo = testFolder() / "pipe.gltf";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string bin = "timeout 20 " + std::string(MANYLIGHT_BIN);
  const std::string out = (testFolder() / "x.png").string();
  for (const std::string& args :
       {"render " + fifo.string() + " -o " + out,
        "bake " + fifo.string() + " -o " + (testFolder() / "x.mlbake").string(),
        "compare " + fifo.string() + " " + fifo.string(), "fit-gamma " + fifo.string(),
        "play " + fifo.string() + " -o " + (testFolder() / "%d.png").string()}) {
    SCOPED_TRACE(args);
    const std::string err = (testFolder() / "err.txt").string();
    EXPECT_EQ(shell(bin + " " + args + " 2>" + err), 1);
    EXPECT_EQ(readFile(err), "manylight: " + fifo.string() + ": not a regular file\n");
  }
}

}  // namespace
}  // namespace manylight::testing
