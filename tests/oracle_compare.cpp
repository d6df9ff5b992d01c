#include "tests/oracle_compare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "tests/oracle.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

struct Comparison {
  int compared = 0;
  int failing = 0;
  double maxRelative = 0.0;
};

// Tolerance: the GPU computes in float, the oracle in double. Float sums over a thousand
// lights and positions from a float G-buffer stay under 4e-4 relative (measured: 3e-5 for
// one light, 3.7e-4 for 1,000 with specular); textures are stored as half floats (relative
// error up to 2^-11 ≈ 4.9e-4 per texel), which brings textured pixels to 7.5e-4 (measured). 1e-3
// covers both with a margin. Values under 1e-3 are compared against 1e-3 instead, so near-black
// pixels don't turn rounding noise into large relative errors.
constexpr double kRelativeTolerance = 1e-3;
constexpr double kFloor = 1e-3;
// Interior pixels may still disagree where a triangle edge inside one surface meets a
// grazing view; allow 0.1% of them to fail (Filament's threshold), none so far.
constexpr double kMaxFailingFraction = 0.001;

Comparison compare(const Image& gpu, const OracleImage& oracle, const std::string& name) {
  Comparison c;
  Image diff = gpu;
  for (int y = 0; y < gpu.height; ++y) {
    for (int x = 0; x < gpu.width; ++x) {
      const float* g = gpu.pixel(x, y);
      const float* o = oracle.image.pixel(x, y);
      float* d = diff.pixel(x, y);
      d[0] = d[1] = d[2] = 0.0f;
      d[3] = 1.0f;
      if (!oracle.interior(x, y)) continue;
      ++c.compared;
      bool bad = g[3] != o[3];
      for (int ch = 0; ch < 3; ++ch) {
        const double rel = std::abs(double(g[ch]) - o[ch]) / std::max(double(o[ch]), kFloor);
        c.maxRelative = std::max(c.maxRelative, rel);
        bad = bad || !(rel <= kRelativeTolerance);
        d[ch] = float(rel / kRelativeTolerance);
      }
      c.failing += bad;
    }
  }
  if (c.failing > c.compared * kMaxFailingFraction) {
    const auto dir = artefactFolder();
    writeImage(gpu, (dir / (name + "-gpu.exr")).string());
    writeImage(oracle.image, (dir / (name + "-oracle.exr")).string());
    writeImage(diff, (dir / (name + "-diff.exr")).string());
    std::cerr << "render test " << name << ": images in " << dir << "\n";
  }
  return c;
}

// Renders `request` on the GPU and with the oracle (using `lights`: the scene's, or the
// rig the GPU used), compares them, and returns the GPU outcome for further checks.
}  // namespace

RenderOutcome expectMatchesOracle(const Scene& scene, const RenderRequest& request,
                                  const std::string& name) {
  const RenderOutcome gpu = renderScene(scene, request);
  const Camera camera = resolveCamera(scene, request);
  const std::vector<Light> lights = gpu.defaultRig ? defaultLightRig(camera) : scene.lights;
  const OracleImage oracle = renderOracle(scene, camera, lights, request.width, request.height,
                                          glm::dvec3(request.ambient));
  const Comparison c = compare(gpu.image, oracle, name);
  EXPECT_GT(c.compared, request.width * request.height / 2);
  EXPECT_LE(c.failing, c.compared * kMaxFailingFraction)
      << name << ": " << c.failing << " of " << c.compared << " pixels off; max relative error "
      << c.maxRelative;
  std::cout << name << ": max relative error " << c.maxRelative << " over " << c.compared
            << " pixels\n";
  return gpu;
}

}  // namespace manylight::testing
