// The display transform through the command line: what the bare render gives a thumbnail,
// and that EXR stays linear radiance.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "generators/scene_builder.h"
#include "image/image.h"
#include "tests/cli_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

// A white Lambert plane facing the camera, no lights: the default rig lights it.
std::string whitePlane() {
  GltfBuilder b;
  BuilderMaterial white;
  b.addBox({0, 0, 0}, {2, 2, 0.1f}, b.addMaterial(white));
  const std::string path = (testFolder() / "white.gltf").string();
  b.write(path);
  return path;
}

TEST(DisplayRender, TheBareRenderOfAWhiteSurfaceUnderTheRigDoesNotClip) {
  const std::string scene = whitePlane();
  const fs::path dir = testFolder();
  for (const char* args : {"", " --tone-map none --exposure 0"}) {
    const std::string out = (dir / "white.png").string(), stats = (dir / "s.json").string();
    const ProcessResult r =
        manylight("render " + scene + " -o " + out + " --size 64x48 --stats " + stats + args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image png = readImage(out);
    int covered = 0, clipped = 0, black = 0;
    for (std::size_t i = 0; i < png.rgba.size(); i += 4) {
      if (png.rgba[i + 3] == 0.0f) continue;
      ++covered;
      clipped += png.rgba[i] >= 254.0f / 255.0f && png.rgba[i + 1] >= 254.0f / 255.0f;
      black += png.rgba[i] <= 2.0f / 255.0f;
    }
    EXPECT_GT(covered, 64 * 48 / 8) << args;
    EXPECT_EQ(clipped, 0) << args;
    EXPECT_EQ(black, 0) << args;
    const auto s = nlohmann::json::parse(readFile(stats));
    EXPECT_EQ(s["tone_map"], std::string(args).empty() ? "pbr-neutral" : "none");
  }
}

TEST(DisplayRender, ExrStaysLinearAndAnExplicitExposureScalesIt) {
  const std::string scene = whitePlane();
  const fs::path dir = testFolder();
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string(),
                    c = (dir / "c.exr").string();
  ASSERT_EQ(manylight("render " + scene + " -o " + a + " --size 32x24").exitCode, 0);
  ASSERT_EQ(manylight("render " + scene + " -o " + b + " --size 32x24 --tone-map aces --exposure 0")
                .exitCode,
            0);
  ASSERT_EQ(manylight("render " + scene + " -o " + c + " --size 32x24 --exposure 1").exitCode, 0);
  EXPECT_EQ(readFile(a), readFile(b));  // neither auto exposure nor a tone map touches EXR
  const Image ia = readImage(a), ic = readImage(c);
  for (std::size_t i = 0; i < ia.rgba.size(); ++i) {
    EXPECT_FLOAT_EQ(ic.rgba[i], i % 4 == 3 ? ia.rgba[i] : 2.0f * ia.rgba[i]);
  }
}

TEST(DisplayRender, BadExposuresAndToneMapsAreUsageErrors) {
  const std::string scene = whitePlane(), out = (testFolder() / "x.png").string();
  for (const char* bad :
       {"--exposure nan", "--exposure inf", "--exposure 1x", "--tone-map filmic"}) {
    const ProcessResult r = manylight("render " + scene + " -o " + out + " " + bad);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

// A turntable with automatic exposure uses one EV, the first frame's, for every frame: the
// same frames come out with that EV given explicitly.
TEST(DisplayRender, PlaybackFixesAutomaticExposureFromTheFirstFrame) {
  const std::string scene = std::string(MANYLIGHT_PROJECT_SCENES) + "/sample.gltf";
  const fs::path dir = testFolder();
  const std::string stats = (dir / "play.json").string();
  const std::string common = " --frames 3 --orbit 90 --size 48x32 --method reference";
  ASSERT_EQ(manylight("play " + scene + " -o " + (dir / "auto" / "f%d.png").string() + common +
                      " --stats " + stats)
                .exitCode,
            0);
  const auto s = nlohmann::json::parse(readFile(stats));
  const double ev = s["exposure_ev"];
  EXPECT_NE(ev, 0.0);
  char fixed[64];
  std::snprintf(fixed, sizeof fixed, " --exposure %.9g", ev);
  ASSERT_EQ(
      manylight("play " + scene + " -o " + (dir / "fixed" / "f%d.png").string() + common + fixed)
          .exitCode,
      0);
  for (int f = 0; f < 3; ++f) {
    const std::string name = "f" + std::to_string(f) + ".png";
    EXPECT_EQ(readFile(dir / "auto" / name), readFile(dir / "fixed" / name)) << name;
  }
}

}  // namespace
}  // namespace manylight::testing
