// The manylight program as a user runs it: outputs, stats, exit codes and exact messages.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "render/colour_calibration.h"
#include "render/image.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/oracle.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

struct ProcessResult {
  int exitCode;
  std::string err;
  std::string out;
};

std::string readFile(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs the program; its output files live outside the test folder, which some tests count.
ProcessResult manylight(const std::string& args) {
  const fs::path errFile = fs::path(testFolder().string() + "-stderr.txt");
  const fs::path outFile = fs::path(testFolder().string() + "-stdout.txt");
  const std::string cmd =
      std::string(MANYLIGHT_BIN) + " " + args + " 2>" + errFile.string() + " >" + outFile.string();
  const int status = std::system(cmd.c_str());
  ProcessResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(errFile),
                  readFile(outFile)};
  fs::remove(errFile);
  fs::remove(outFile);
  return r;
}

std::string writeText(const std::string& name, const std::string& text) {
  const fs::path p = testFolder() / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(Cli, RendersPngAndExrWithStats) {
  RoomOptions o;
  o.lightCount = 16;
  const std::string scene = roomScene(o);
  const fs::path dir = testFolder();
  const ProcessResult r = manylight("render " + scene + " -o " + (dir / "a.png").string() +
                                    " --size 80x60 --stats " + (dir / "stats.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image png = readImage((dir / "a.png").string());
  EXPECT_EQ(png.width, 80);
  EXPECT_EQ(png.height, 60);
  const auto stats = nlohmann::json::parse(readFile(dir / "stats.json"));
  for (const char* key :
       {"method", "backend", "renderer", "width", "height", "lights", "load_ms", "render_ms",
        "total_ms", "degenerate_triangles", "boundary_edges", "non_manifold_edges"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_EQ(stats["method"], "reference");
  EXPECT_EQ(stats["lights"], 16);
  EXPECT_EQ(stats["width"], 80);
  ASSERT_EQ(
      manylight("render " + scene + " -o " + (dir / "a.exr").string() + " --size 80x60").exitCode,
      0);
  EXPECT_EQ(readImage((dir / "a.exr").string()).width, 80);
}

TEST(Cli, PngIsWithinOneCodeOfTheOracle) {
  RoomOptions o;
  o.lightCount = 7;
  const std::string scene = roomScene(o);
  const fs::path out = testFolder() / "o.png";
  ASSERT_EQ(manylight("render " + scene + " -o " + out.string() + " --size 120x90").exitCode, 0);
  const Image png = readImage(out.string());
  const Scene s = loadGltf(scene);
  RenderRequest request;
  request.width = 120;
  request.height = 90;
  const OracleImage oracle = renderOracle(s, resolveCamera(s, request), s.lights, 120, 90);
  int compared = 0, off = 0;
  for (int y = 0; y < 90; ++y) {
    for (int x = 0; x < 120; ++x) {
      if (!oracle.interior(x, y)) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) {
        const int got = int(std::lround(png.pixel(x, y)[c] * 255.0f));
        const int want = encodeSrgb8(oracle.image.pixel(x, y)[c]);
        off += std::abs(got - want) > 1;
      }
    }
  }
  EXPECT_GT(compared, 120 * 90 / 2);
  EXPECT_EQ(off, 0) << "channels more than 1 code off";
}

// The value after "NAME = " in the fit tool's output.
double printed(const std::string& out, const std::string& name) {
  const std::size_t at = out.find("\n" + name + " = ");
  if (at == std::string::npos && out.rfind(name + " = ", 0) != 0) {
    ADD_FAILURE() << "no '" << name << "' in:\n" << out;
    return std::nan("");
  }
  return std::stod(
      out.substr(out.find(name + " = ", at == std::string::npos ? 0 : at) + name.size() + 3));
}

TEST(Cli, FitGammaPrintsTheUe4Fit) {
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

TEST(Cli, CalibrationMeasuresTheExactSrgbCurve) {
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

TEST(Cli, PngCodesFollowTheExactSrgbEncoding) {
  // 256 emissive strips whose linear radiance is the exact decoding of codes 0..255, seen
  // one pixel per strip through an orthographic camera: every code must come back.
  GltfBuilder b;
  BuilderMaterial black;
  black.baseColor = {0, 0, 0, 1};  // so the default light rig adds nothing
  for (int code = 0; code < 256; ++code) {
    black.emissive = glm::vec3(float(decodeSrgb8(std::uint8_t(code))));
    b.addBox({code + 0.5f, 0.0f, 0.0f}, {1.0f, 2.0f, 1.0f}, b.addMaterial(black));
  }
  b.addOrthographicCamera({128.0f, 0.0f, 10.0f}, {128.0f, 0.0f, 0.0f}, 128.0f, 1.0f);
  const fs::path scene = testFolder() / "gradient.gltf";
  b.write(scene.string());
  const fs::path out = testFolder() / "gradient.png";
  const ProcessResult r =
      manylight("render " + scene.string() + " -o " + out.string() + " --size 256x2");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Image png = readImage(out.string());
  int wrong = 0;
  for (int y = 0; y < 2; ++y) {
    for (int code = 0; code < 256; ++code) {
      for (int c = 0; c < 3; ++c) {
        const int got = int(std::lround(png.pixel(code, y)[c] * 255.0f));
        if (got != code) {
          ++wrong;
          ADD_FAILURE() << "pixel " << code << "," << y << " channel " << c << ": code " << got;
        }
      }
    }
  }
  EXPECT_EQ(wrong, 0);
}

TEST(Cli, LightListsAddToTheScenesLights) {
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

TEST(Cli, CompareAssertsARenderAgainstAStoredImage) {
  const fs::path dir = testFolder();
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string(),
                    small = (dir / "small.png").string();
  ASSERT_EQ(manylight("render " + scene + " -o " + a + " --size 64x48").exitCode, 0);
  ASSERT_EQ(manylight("render " + scene + " -o " + b + " --size 64x48 --exposure 0.05").exitCode,
            0);
  ASSERT_EQ(manylight("render " + scene + " -o " + small + " --size 32x48").exitCode, 0);

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

TEST(Cli, BatchesRenderEverySceneInOneProcess) {
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

TEST(Cli, BakedScenesRenderAsTheirSources) {
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

int shell(const std::string& command) {
  const int status = std::system(("bash -c '" + command + "'").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Cli, PlaybackOrbitsTheCameraFrameByFrame) {
  const fs::path dir = testFolder();
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const std::string frames = (dir / "frames" / "f%03d.png").string();
  ProcessResult r = manylight("play " + scene + " -o " + frames +
                              " --frames 4 --size 48x32 --stats " + (dir / "play.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stats = nlohmann::json::parse(readFile(dir / "play.json"));
  EXPECT_EQ(stats["frames"], 4);
  EXPECT_EQ(stats["frame_render_ms"].size(), 4u);
  EXPECT_GT(stats["render_fps"].get<double>(), 0.0);
  // Frame 0 is the still render of the same camera, bit for bit; later frames have turned.
  const fs::path still = dir / "still.png";
  ASSERT_EQ(
      manylight("render " + scene + " -o " + still.string() + " --size 48x32 --method lightcuts")
          .exitCode,
      0);
  EXPECT_EQ(readFile(dir / "frames" / "f000.png"), readFile(still));
  EXPECT_NE(readFile(dir / "frames" / "f002.png"), readFile(still));
  EXPECT_TRUE(fs::exists(dir / "frames" / "f003.png"));
  EXPECT_FALSE(fs::exists(dir / "frames" / "f004.png"));

  // Raw frames on stdout: 4 × 48 × 32 RGBA8, the first equal to the PNG's codes.
  const fs::path raw = dir / "frames.rgba";
  ASSERT_EQ(shell(std::string(MANYLIGHT_BIN) + " play " + scene +
                  " -o - --frames 4 --size 48x32 > " + raw.string()),
            0);
  const std::string bytes = readFile(raw);
  ASSERT_EQ(bytes.size(), 4u * 48 * 32 * 4);
  const Image first = readImage(still.string());
  int off = 0;
  for (std::size_t i = 0; i < 48 * 32 * 4; ++i) {
    off += std::uint8_t(bytes[i]) != int(std::lround(first.rgba[i] * 255.0f));
  }
  EXPECT_EQ(off, 0);

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

  r = manylight("play " + scene + " -o " + (dir / "nopattern.png").string());
  EXPECT_EQ(r.exitCode, 2);
}

TEST(Cli, PlaybackFollowsTheCameraAnimation) {
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

TEST(Cli, FifosAreRefusedWithoutBlocking) {
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

TEST(Cli, RerenderingIsBitIdenticalAndBackendsAgree) {
  RoomOptions o;
  o.lightCount = 32;
  const std::string scene = roomScene(o);
  const fs::path dir = testFolder();
  for (const char* ext : {".png", ".exr"}) {
    std::vector<std::string> files;
    for (const char* backend : {"egl", "egl", "osmesa"}) {
      const std::string out =
          (dir / (std::string(backend) + std::to_string(files.size()) + ext)).string();
      const ProcessResult r =
          manylight("render " + scene + " -o " + out + " --size 96x64 --backend " + backend);
      ASSERT_EQ(r.exitCode, 0) << r.err;
      files.push_back(readFile(out));
    }
    EXPECT_EQ(files[0], files[1]) << ext << ": two EGL renders differ";
    EXPECT_EQ(files[0], files[2]) << ext << ": EGL and OSMesa differ";
  }
}

struct BadInput {
  const char* name;
  const char* json;  // file content; nullptr: the file is missing
  const char* args;
  const char* message;  // after "manylight: PATH: "
};

const BadInput kBadInputs[] = {
    {"missing.gltf", nullptr, "", "cannot open: No such file or directory"},
    {"not-json.gltf", "{ this is not json", "", ""},
    {"min-version.gltf", R"({"asset": {"version": "2.0", "minVersion": "2.1"}})", "",
     "asset.minVersion 2.1 is not supported, expected 2.0"},
    {"version-1.gltf", R"({"asset": {"version": "1.0"}})", "",
     "asset.version '1.0' is not supported, expected 2.x"},
    {"required.gltf",
     R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_draco_mesh_compression"],
         "extensionsRequired": ["KHR_draco_mesh_compression"]})",
     "", "required extension KHR_draco_mesh_compression is not supported"},
    {"bad-spot.gltf",
     R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
         "extensions": {"KHR_lights_punctual": {"lights": [
           {"type": "spot", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.5}}]}},
         "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0]}], "scene": 0})",
     "", "light 0: spot cone angles must satisfy 0 <= inner < outer <= pi/2"},
    {"over-budget.gltf",
     R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
         "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}]}},
         "nodes": [{"extensions": {"KHR_lights_punctual": {"light": 0}}},
                   {"extensions": {"KHR_lights_punctual": {"light": 0}}},
                   {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
         "scenes": [{"nodes": [0, 1, 2]}]})",
     "--light-budget 2", "3 lights exceed the light budget of 2 (--light-budget)"},
    {"cycle.gltf",
     R"({"asset": {"version": "2.0"}, "nodes": [{"children": [1]}, {"children": [0]}],
         "scenes": [{"nodes": [0]}]})",
     "", "node 0 is part of a cycle"},
    {"two-parents.gltf",
     R"({"asset": {"version": "2.0"}, "nodes": [{"children": [2]}, {"children": [2]}, {}],
         "scenes": [{"nodes": [0, 1]}]})",
     "", "node 2 has two parents (nodes 0 and 1)"},
    {"root-twice.gltf",
     R"({"asset": {"version": "2.0"}, "nodes": [{}], "scenes": [{"nodes": [0, 0]}]})", "",
     "node 0 is reached twice (a scene root listed twice, or also a child)"},
    {"view-past-buffer.gltf",
     R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "data:application/octet-stream;base64,AAAAAA==", "byteLength": 4}],
         "bufferViews": [{"buffer": 0, "byteOffset": 2, "byteLength": 4}]})",
     "", "bufferView 0: bytes 2..6 lie beyond its buffer's 4"},
    {"escape.gltf",
     R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "../secret.bin", "byteLength": 4}]})", "",
     "URI '../secret.bin': leaves the scene's folder"},
    {"encoded-escape.gltf",
     R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "%2E%2E/secret.bin", "byteLength": 4}]})",
     "", "URI '../secret.bin': leaves the scene's folder"},
    {"absolute.gltf",
     R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "/etc/passwd", "byteLength": 4}]})", "",
     "URI '/etc/passwd': absolute paths are not allowed"},
    {"scheme.gltf",
     R"({"asset": {"version": "2.0"}, "images": [{"uri": "http://example.com/a.png"}]})", "",
     "URI 'http://example.com/a.png': scheme 'http' is not allowed (only data: URIs and relative "
     "paths)"},
    {"missing-buffer.gltf",
     R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "gone.bin", "byteLength": 4}]})", "",
     "URI 'gone.bin': no such file"},
    {"no-camera-5.gltf", R"({"asset": {"version": "2.0"}})", "--camera 5",
     "camera 5 does not exist (the scene has 0)"},
};

TEST(Cli, BadInputsFailWithOneLineAndNoOutput) {
  for (const BadInput& b : kBadInputs) {
    SCOPED_TRACE(b.name);
    const fs::path path = testFolder() / b.name;
    if (b.json) writeText(b.name, b.json);
    const fs::path out = testFolder() / "out.png";
    const ProcessResult r =
        manylight("render " + path.string() + " -o " + out.string() + " " + b.args);
    EXPECT_EQ(r.exitCode, 1);
    const std::string prefix = "manylight: " + path.string() + ": ";
    EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << r.err;
    if (*b.message) {
      EXPECT_EQ(r.err, prefix + b.message + "\n");
    }
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(testFolder()), fs::directory_iterator()),
              b.json ? 1 : 0)
        << "a temporary file was left behind";
    fs::remove(path);
  }
}

TEST(Cli, LightcutsWritesCutStatistics) {
  RoomOptions o;
  o.lightCount = 300;
  const std::string scene = roomScene(o);
  const fs::path dir = testFolder();
  const ProcessResult r =
      manylight("render " + scene + " -o " + (dir / "a.exr").string() +
                " --size 64x48 --method lightcuts --error 0.05 --error-mode total --max-cut 500"
                " --stats " +
                (dir / "stats.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto stats = nlohmann::json::parse(readFile(dir / "stats.json"));
  EXPECT_EQ(stats["method"], "lightcuts");
  EXPECT_EQ(stats["error_mode"], "total");
  EXPECT_EQ(stats["max_cut"], 500);
  EXPECT_DOUBLE_EQ(stats["error"].get<double>(), 0.05f);
  EXPECT_GT(stats["bake_ms"].get<double>(), 0.0);
  EXPECT_GE(stats["avg_cut_size"].get<double>(), 1.0);
  EXPECT_LE(stats["avg_cut_size"].get<double>(), 500.0);
  EXPECT_LE(stats["max_cut_size"].get<int>(), 500);
  EXPECT_GE(stats["pixels_at_max_cut"].get<int>(), 0);
  EXPECT_GT(stats["light_evaluations_per_pixel"].get<double>(), 0.0);
  EXPECT_GT(stats["covered_pixels"].get<int>(), 64 * 48 / 2);
}

TEST(Cli, LimitsRefuseScenesBeforeReadingThem) {
  RoomOptions o;
  o.lightCount = 2;
  const std::string scene = roomScene(o);  // textured: an 8×8 checker
  const std::string out = (testFolder() / "x.png").string();
  struct Limit {
    std::string args, message;
  };
  const Limit limits[] = {
      {"--max-triangles 100", "triangles exceed the limit of 100"},
      {"--max-texture-size 4",
       "image 0: cannot decode image: 8x8 exceeds the texture dimension limit of 4"},
      {"--max-texture-pixels 63",
       "image 0: cannot decode image: 8x8 exceeds the texture limit of 63 pixels"},
      {"--max-file-bytes 100", "the scene's files exceed the limit of 100 bytes"},
      {"--light-budget 1", "2 lights exceed the light budget of 1 (--light-budget)"},
  };
  for (const Limit& l : limits) {
    const ProcessResult r = manylight("render " + scene + " -o " + out + " " + l.args);
    EXPECT_EQ(r.exitCode, 1) << l.args;
    EXPECT_EQ(r.err.rfind("manylight: " + scene + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(l.message), std::string::npos) << l.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(manylight("render").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --method nope").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --error-mode nope").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --tree-split nope").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --error 0").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --max-cut 0").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --size 0x5").exitCode, 2);
  EXPECT_EQ(manylight("render x.gltf -o y.png --frobnicate").exitCode, 2);
  EXPECT_EQ(manylight("--help").exitCode, 0);
}

TEST(Cli, UnwritableOutputLeavesNothing) {
  RoomOptions o;
  o.lightCount = 1;
  const std::string scene = roomScene(o);
  const fs::path blocker = testFolder() / "file";
  std::ofstream(blocker) << "x";
  const std::string out = (blocker / "sub" / "x.png").string();  // parent is a file
  const ProcessResult r = manylight("render " + scene + " -o " + out + " --size 16x16");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("manylight: " + out + ": "), std::string::npos) << r.err;
  const ProcessResult bad =
      manylight("render " + scene + " -o " + (testFolder() / "x.bmp").string());
  EXPECT_EQ(bad.err, "manylight: " + (testFolder() / "x.bmp").string() +
                         ": unsupported output format, expected .png or .exr\n");
  EXPECT_FALSE(fs::exists(testFolder() / "x.bmp"));
}

}  // namespace
}  // namespace manylight::testing
