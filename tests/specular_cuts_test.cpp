// Shared cuts for specular pixels (cuts/tile_cuts.h, cuts/pixel_groups.h) without GL: with the
// albedo and the view given, Phong pixels share their group's cut, and each shared cut, its
// far field and its lobes' constant included, evaluated in double precision at every pixel of
// its group, is within the bounds the pixel checks against (albedo ∘ U + ks ∘ U_lobe).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>

#include "bake/light_tree.h"
#include "bake/light_tree_layout.h"
#include "bake/light_tree_pack.h"
#include "cuts/tile_cuts.h"
#include "generators/light_layouts.h"
#include "scene/shading_model.h"
#include "tests/far_field_support.h"

namespace manylight {
namespace {

constexpr int kSize = 64;
const glm::vec3 kEye(0.0f, 3.0f, 9.0f);

// A floor (y = 0) on the left, glossy (ks 0.04, exponent 8) in its lower 42 rows and Lambert
// above; a metal wall (x = 3, albedo 0, ks (0.8, 0.25, 0.2), exponent 1.5) on the right; a
// band of background at the top. Rows bottom-up, as GL reads them.
struct MaterialGBuffer {
  std::vector<float> position, normal, specular, albedo;
  MaterialGBuffer()
      : position(kSize * kSize * 4),
        normal(kSize * kSize * 4),
        specular(kSize * kSize * 4),
        albedo(kSize * kSize * 4) {
    for (int y = 0; y < kSize - 6; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const std::size_t i = (std::size_t(y) * kSize + x) * 4;
        const float u = float(x) / kSize, v = float(y) / kSize;
        const bool floor = x < kSize * 5 / 8;
        const glm::vec3 p = floor ? glm::vec3(-3.0f + 9.6f * u, 0.0f, -3.0f + 6.0f * v)
                                  : glm::vec3(3.0f, 12.0f * (u - 0.625f), -3.0f + 6.0f * v);
        const glm::vec3 n = floor ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(-1.0f, 0.0f, 0.0f);
        const glm::vec3 a = floor ? glm::vec3(0.7f, 0.6f, 0.5f) : glm::vec3(0.0f);
        const glm::vec3 ks = !floor   ? glm::vec3(0.8f, 0.25f, 0.2f)
                             : y < 42 ? glm::vec3(0.04f)
                                      : glm::vec3(0.0f);
        std::memcpy(&position[i], &p, 12);
        position[i + 3] = floor ? 8.0f : 1.5f;
        std::memcpy(&normal[i], &n, 12);
        normal[i + 3] = 1.0f;
        std::memcpy(&albedo[i], &a, 12);
        std::memcpy(&specular[i], &ks, 12);
      }
    }
  }
  GBufferPixels pixels() const {
    GBufferPixels px{kSize, kSize, position.data(), normal.data(), specular.data()};
    px.albedo = albedo.data();
    px.eye = kEye;
    return px;
  }
  glm::dvec3 at(const std::vector<float>& v, std::size_t i) const {
    return {v[4 * i], v[4 * i + 1], v[4 * i + 2]};
  }
};

struct Checked {
  int specularPixels = 0, sharedSpecular = 0, sharedPixels = 0, failing = 0;
  int lobeCuts = 0;   // shared pixels whose cut carries lobe bounds
  int mixedCuts = 0;  // shared cuts holding metal-like pixels (ks over albedo) and others
  double worstOverBound = 0.0;
};

using layout::floatOf;

glm::dvec3 texel(const std::uint32_t* e) { return {floatOf(e[0]), floatOf(e[1]), floatOf(e[2])}; }

// Every shared cut of `cuts` at each of its pixels of `g`, against the exact sum of `lights`.
Checked checkCuts(const MaterialGBuffer& g, const std::vector<Light>& lights,
                  const TileCuts& cuts) {
  std::map<std::array<float, 3>, std::size_t> spotAt;  // positions are distinct
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].type == LightType::Spot)
      spotAt[{lights[i].position.x, lights[i].position.y, lights[i].position.z}] = i;
  }
  const std::vector<std::uint32_t> texels = cuts.texels.flat();
  Checked c;
  std::map<std::uint32_t, int> kinds;  // per shared cut: 1 metal-like pixels, 2 others
  for (std::size_t i = 0; i < std::size_t(kSize * kSize); ++i) {
    if (g.normal[4 * i + 3] == 0.0f) continue;
    const shading::PhongMaterial m{g.at(g.albedo, i), g.at(g.specular, i),
                                   double(g.position[4 * i + 3])};
    const bool specular = m.specular != glm::dvec3(0.0);
    c.specularPixels += specular ? 1 : 0;
    const std::uint32_t cut = cuts.cutOfPixel[i];
    if (cut == kNoSharedCut) continue;
    ++c.sharedPixels;
    c.sharedSpecular += specular ? 1 : 0;
    const double ks = std::max({m.specular.r, m.specular.g, m.specular.b});
    kinds[cut] |= ks > std::max({m.albedo.r, m.albedo.g, m.albedo.b}) ? 1 : 2;
    const glm::dvec3 p = g.at(g.position, i), n = g.at(g.normal, i);
    const glm::dvec3 v = glm::normalize(glm::dvec3(kEye) - p);
    auto radiance = [&](const Light& l) {
      glm::dvec3 towards;
      const glm::dvec3 e = shading::irradiance(l, p, n, towards);
      return e == glm::dvec3(0.0) ? e : shading::brdf(m, n, towards, v) * e;
    };
    glm::dvec3 exact(0.0), estimate(0.0);
    for (const Light& l : lights) exact += radiance(l);
    const std::uint32_t* head = texels.data() + std::size_t(cut) * 8;
    const std::uint32_t* e = texels.data() + std::size_t(head[0]) * 4;
    glm::dvec3 bound = m.albedo * glm::dvec3(floatOf(head[4]), floatOf(head[5]), floatOf(head[6]));
    if (head[7] & kLobesBit) {
      ++c.lobeCuts;
      bound += m.specular * texel(e);
      estimate += m.specular * texel(e + 4);
      e += 8;
    }
    if ((head[7] & 0x7fffu) > 0) {
      estimate += m.albedo * farFieldIrradiance(e, p, n) / shading::kPi;
      e += 4 * kFarFieldTexels;
    }
    for (int tree = 0; tree < 3; ++tree) {
      for (std::uint32_t k = 0; k < head[1 + tree]; ++k) {
        Light rep;
        const glm::vec3 a(floatOf(e[0]), floatOf(e[1]), floatOf(e[2]));
        rep.type = tree == 0   ? LightType::Directional
                   : tree == 1 ? LightType::Point
                               : LightType::Spot;
        rep.position = a;
        rep.direction = -a;
        if (floatOf(e[3]) > 0.0f) rep.range = 1.0f / std::sqrt(floatOf(e[3]));
        e += tree == 2 ? 8 : 4;
        if (tree == 2) rep = lights[spotAt.at({a.x, a.y, a.z})];
        rep.colour = glm::vec3(floatOf(e[0]), floatOf(e[1]), floatOf(e[2]));
        rep.intensity = 1.0f;
        estimate += radiance(rep);
        e += 4;
      }
    }
    for (int ch = 0; ch < 3; ++ch) {
      const double error = std::abs(estimate[ch] - exact[ch]);
      // Float bounds and decoding against double sums: 1e-4 of the pixel, and a floor.
      if (error > bound[ch] + 1e-4 * exact[ch] + 1e-9) ++c.failing;
      if (bound[ch] > 0.0) c.worstOverBound = std::max(c.worstOverBound, error / bound[ch]);
    }
  }
  for (const auto& k : kinds) c.mixedCuts += k.second == 3 ? 1 : 0;
  return c;
}

Checked cutAndCheck(LightLayout layout, int count, const CutRule& rule, int tile) {
  const MaterialGBuffer g;
  const std::vector<Light> lights = layoutLights(layout, count, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  return checkCuts(g, lights, cutter.cut(g.pixels(), tile, rule, 2));
}

// Under the total rule the bound is on the whole sum, so every shared pixel's error must be
// within it; specular pixels share cuts as Lambert ones do.
TEST(SpecularCuts, SharedCutsStayWithinTheirLobeBoundsAtEveryPixel) {
  for (const LightLayout layout : {LightLayout::Uniform, LightLayout::Mixed}) {
    for (const int tile : {4, 16}) {
      SCOPED_TRACE("layout " + std::to_string(int(layout)) + " tile " + std::to_string(tile));
      const Checked c = cutAndCheck(layout, 1500, CutRule{0.02f, true, 8000}, tile);
      EXPECT_EQ(c.specularPixels, 3072);
      EXPECT_GT(c.sharedSpecular, c.specularPixels * 9 / 10);
      EXPECT_GT(c.lobeCuts, c.sharedSpecular);  // Lambert pixels beside them share lobe cuts
      EXPECT_EQ(c.failing, 0);
      EXPECT_LE(c.worstOverBound, 1.0001);
    }
  }
}

// Under the node rule too, specular pixels take their group's cut.
TEST(SpecularCuts, SpecularPixelsTakeTheirGroupsCutUnderTheNodeRule) {
  const Checked c = cutAndCheck(LightLayout::Mixed, 1500, CutRule{0.02f, false, 2000}, 16);
  EXPECT_EQ(c.specularPixels, 3072);
  EXPECT_GT(c.sharedSpecular, c.specularPixels * 9 / 10);
}

// On one plane, metal stripes among Lambert ones: no shared cut holds both kinds (each pixel
// checks the cut with its own colours, cuts/cut_frame.cpp's materials), and the metal pixels
// take shared cuts within their bounds.
TEST(SpecularCuts, MetalPixelsAndOthersTakeCutsApart) {
  MaterialGBuffer g;
  int metal = 0;
  for (int y = 0; y < kSize - 6; ++y) {
    for (int x = 4; x < kSize * 5 / 8; x += 8) {
      for (int k = x; k < x + 4; ++k) {
        const std::size_t i = (std::size_t(y) * kSize + k) * 4;
        const float ks[3] = {0.8f, 0.25f, 0.2f};
        for (int c = 0; c < 3; ++c) g.albedo[i + c] = 0.0f, g.specular[i + c] = ks[c];
        g.position[i + 3] = 1.5f;
        ++metal;
      }
    }
  }
  const std::vector<Light> lights = layoutLights(LightLayout::Mixed, 1500, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  for (const bool total : {false, true}) {
    SCOPED_TRACE(total ? "total rule" : "node rule");
    const Checked c =
        checkCuts(g, lights, cutter.cut(g.pixels(), 16, CutRule{0.02f, total, 8000}, 2));
    EXPECT_EQ(c.mixedCuts, 0);
    EXPECT_EQ(c.specularPixels, 3072 - 42 * 20 + metal);  // the stripes were Lambert above
    EXPECT_GT(c.sharedSpecular, c.specularPixels * 9 / 10);
    if (total) {
      EXPECT_EQ(c.failing, 0);
    }
  }
}

// Without the albedo (and so the view), specular pixels cut for themselves.
TEST(SpecularCuts, WithoutTheAlbedoSpecularPixelsCutForThemselves) {
  const MaterialGBuffer g;
  GBufferPixels px = g.pixels();
  px.albedo = nullptr;
  const std::vector<Light> lights = layoutLights(LightLayout::Uniform, 100, 7);
  const TileCutter cutter(packLightTrees(buildLightTrees(lights)), lights);
  const TileCuts cuts = cutter.cut(px, 16, CutRule{}, 1);
  const Checked c = checkCuts(g, lights, cuts);
  EXPECT_EQ(c.sharedSpecular, 0);
  EXPECT_EQ(c.lobeCuts, 0);
  EXPECT_GT(c.sharedPixels, 0);  // the Lambert half of the floor
}

}  // namespace
}  // namespace manylight
