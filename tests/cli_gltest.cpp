// The manylight program as a user runs it: outputs, stats, exit codes and exact messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "image/image.h"
#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/cli_support.h"
#include "tests/oracle.h"
#include "tests/test_support.h"
#include "tools/colour_calibration.h"

namespace manylight::testing {
namespace {

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
  // The linear radiance sRGB-encoded, with no exposure or tone map.
  ASSERT_EQ(manylight("render " + scene + " -o " + out.string() +
                      " --size 120x90 --tone-map none --exposure 0")
                .exitCode,
            0);
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
  const ProcessResult r = manylight("render " + scene.string() + " -o " + out.string() +
                                    " --size 256x2 --tone-map none --exposure 0");
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
     R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_texture_basisu"],
         "extensionsRequired": ["KHR_texture_basisu"]})",
     "",
     "required extension KHR_texture_basisu is not supported: Basis Universal (KTX2) textures "
     "have no decoder here"},
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
  // Shared cuts (the default --cut-tile 16) are found on the CPU within the frame.
  EXPECT_GT(stats["cut_ms"].get<double>(), 0.0);
  EXPECT_LT(stats["cut_ms"].get<double>(), stats["render_ms"].get<double>());
  EXPECT_GE(stats["avg_cut_size"].get<double>(), 1.0);
  EXPECT_LE(stats["avg_cut_size"].get<double>(), 500.0);
  EXPECT_LE(stats["max_cut_size"].get<int>(), 500);
  EXPECT_GE(stats["pixels_at_max_cut"].get<int>(), 0);
  EXPECT_GT(stats["light_evaluations_per_pixel"].get<double>(), 0.0);
  EXPECT_GT(stats["covered_pixels"].get<int>(), 64 * 48 / 2);
  // The CPU's cuts by kind: a 64×48 frame has two 32×32 squares finding seeds; their node
  // bounds are among the node evaluations.
  long long bounds = 0;
  for (const char* kind : {"seeds", "from_seeds", "retries", "from_roots", "probes", "cells"}) {
    const auto& w = stats["cut_work"][kind];
    EXPECT_LE(w["full"].get<int>(), w["cuts"].get<int>()) << kind;
    bounds += w["bounds"].get<long long>();
  }
  EXPECT_GE(stats["cut_work"]["seeds"]["cuts"].get<int>(), 2);
  EXPECT_EQ(stats["cut_work"]["cells"]["cuts"].get<int>(), 0);
  EXPECT_GT(bounds, 0);
  EXPECT_LE(double(bounds), stats["node_evaluations_per_pixel"].get<double>() *
                                stats["covered_pixels"].get<double>() * 1.0001);
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
  EXPECT_EQ(manylight("render x.gltf -o y.png --camera -3").exitCode, 2);
  EXPECT_EQ(manylight("play x.gltf -o 'f%d.png' --camera -1").exitCode, 2);
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
