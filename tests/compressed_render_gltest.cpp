// Compressed geometry renders as the same geometry uncompressed: each compressed scene
// against its plain twin, rendered in the same test with one camera and the default rig.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "render/render_job.h"
#include "scene/gltf_loader.h"
#include "tests/compressed_scenes.h"
#include "tests/gl_support.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

namespace fs = std::filesystem;

struct Difference {
  int covered = 0;           // pixels covered in either image
  int failing = 0;           // of them: coverage differs, or a channel is off by more than allowed
  double maxRelative = 0.0;  // over pixels covered in both
};

// Renders `plain` and `compressed` through the plain scene's camera (its framing) and
// compares them channel by channel: relative error over max(value, 1e-3) within
// `relativeTolerance`, and at most `maxFailingFraction` of covered pixels failing.
void expectSameRender(Scene plain, Scene compressed, double relativeTolerance,
                      double maxFailingFraction, const std::string& name) {
  RenderRequest request;
  request.width = 128;
  request.height = 96;
  const Camera camera = resolveCamera(plain, request);
  plain.cameras = compressed.cameras = {camera};
  request.camera = 0;
  const Image a = renderScene(plain, request).image;
  const Image b = renderScene(compressed, request).image;
  Difference d;
  Image diff = a;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      const float* p = a.pixel(x, y);
      const float* q = b.pixel(x, y);
      float* out = diff.pixel(x, y);
      if (p[3] == 0.0f && q[3] == 0.0f) continue;
      ++d.covered;
      bool bad = p[3] != q[3];
      for (int c = 0; c < 3 && !bad; ++c) {
        const double rel = std::abs(double(p[c]) - q[c]) / std::max(double(p[c]), 1e-3);
        d.maxRelative = std::max(d.maxRelative, rel);
        out[c] = float(rel / relativeTolerance);
        bad = !(rel <= relativeTolerance);
      }
      d.failing += bad;
    }
  }
  std::cout << name << ": " << d.failing << " of " << d.covered
            << " covered pixels differ; max relative error " << d.maxRelative << "\n";
  EXPECT_GT(d.covered, request.width * request.height / 10);
  EXPECT_LE(d.failing, d.covered * maxFailingFraction) << name;
  if (d.failing > d.covered * maxFailingFraction) {
    const fs::path dir = artefactFolder();
    writeImage(a, (dir / (name + "-plain.exr")).string());
    writeImage(b, (dir / (name + "-compressed.exr")).string());
    writeImage(diff, (dir / (name + "-diff.exr")).string());
    std::cerr << "render test " << name << ": images in " << dir << "\n";
  }
}

// meshopt without filters is lossless: the same bytes, so the same image.
TEST(CompressedRender, MeshoptRendersBitIdentically) {
  context();
  const TestMesh mesh = gridMesh(16);
  const fs::path dir = testFolder();
  writeGltf((dir / "plain.glb").string(), plainMeshFile(mesh));
  writeGltf((dir / "meshopt.glb").string(), meshoptMeshFile(mesh, false, false));
  expectSameRender(loadGltf((dir / "plain.glb").string()), loadGltf((dir / "meshopt.glb").string()),
                   0.0, 0.0, "meshopt-grid");
}

// Draco quantises positions to 14 bits and normals to 10 bits (about 2e-3 radians): shading
// follows the normal's cosine, so values move by up to a few 1e-3 (measured 8.7e-4; 3e-3
// allowed); the silhouette moves by under 1e-4 of the grid, which may change the coverage of
// a few edge pixels (measured none; 2% allowed).
TEST(CompressedRender, DracoRendersAsThePlainMesh) {
  context();
  const TestMesh mesh = gridMesh(16);
  const fs::path dir = testFolder();
  writeGltf((dir / "plain.glb").string(), plainMeshFile(mesh));
  writeGltf((dir / "draco.glb").string(), dracoMeshFile(mesh, true));
  expectSameRender(loadGltf((dir / "plain.glb").string()), loadGltf((dir / "draco.glb").string()),
                   3e-3, 0.02, "draco-grid");
}

// The glTF sample Box: its Draco corners are at ±0.50049 instead of ±0.5 (11-bit positions),
// so its silhouette is 0.1% larger: a few edge pixels may change coverage (measured none at
// 128×96; 2% allowed); its axis normals are exact, so covered pixels match to float rounding
// (measured 1.3e-7; 1e-4 allowed).
TEST(CompressedRender, TheDracoSampleBoxRendersAsThePlainBox) {
  const fs::path shared = MANYLIGHT_SHARED_SCENES;
  if (!fs::exists(shared / "Box/glTF-Draco/Box.gltf")) GTEST_SKIP() << "no " << shared;
  context();
  expectSameRender(loadGltf((shared / "Box/glTF/Box.gltf").string()),
                   loadGltf((shared / "Box/glTF-Draco/Box.gltf").string()), 1e-4, 0.02,
                   "draco-box");
}

}  // namespace
}  // namespace manylight::testing
