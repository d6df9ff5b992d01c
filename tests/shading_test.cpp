// The shading model's pieces, the light packing and the sRGB encoding, without GL.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "bake/light_pack.h"
#include "bake/light_texture_layout.h"
#include "image/image.h"
#include "scene/shading_model.h"

namespace manylight {
namespace {

TEST(Shading, FullyRoughDielectricIsPureLambert) {
  const auto m = shading::phongFromMetallicRoughness(glm::dvec3(0.8, 0.5, 0.2), 0.0, 1.0);
  EXPECT_EQ(m.specular, glm::dvec3(0.0));
  EXPECT_EQ(m.albedo, glm::dvec3(0.8, 0.5, 0.2));
  const auto metal = shading::phongFromMetallicRoughness(glm::dvec3(0.9, 0.6, 0.3), 1.0, 0.5);
  EXPECT_EQ(metal.albedo, glm::dvec3(0.0));
  EXPECT_NEAR(metal.specular.r, 0.9, 1e-12);
  EXPECT_NEAR(metal.exponent, 0.125 / std::pow(0.25, 2) - 0.5, 1e-9);  // 1/(8α²) − 1/2
  EXPECT_FALSE(shading::hasSpecularTerm(0.0, 1.0));
  EXPECT_TRUE(shading::hasSpecularTerm(1.0, 1.0));
  EXPECT_TRUE(shading::hasSpecularTerm(0.0, 0.9));
}

TEST(Shading, RangeWindowAndCone) {
  EXPECT_EQ(shading::rangeWindow(5.0, 0.0), 1.0);
  EXPECT_EQ(shading::rangeWindow(0.0, 2.0), 1.0);
  EXPECT_EQ(shading::rangeWindow(2.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(shading::rangeWindow(1.0, 2.0), 1.0 - 1.0 / 16.0);  // not squared
  EXPECT_DOUBLE_EQ(shading::rangeWindow(1.5, 2.0), 1.0 - 0.75 * 0.75 * 0.75 * 0.75);
  EXPECT_EQ(shading::rangeWindow(3.0, 2.0), 0.0);
  // A kink at the range: slope −4/range inside, 0 beyond.
  EXPECT_NEAR(shading::rangeWindow(2.0 - 1e-6, 2.0) / 1e-6, 2.0, 1e-5);
  EXPECT_EQ(shading::smoothstep(0.5, 0.8, 0.4), 0.0);
  EXPECT_EQ(shading::smoothstep(0.5, 0.8, 0.9), 1.0);
  EXPECT_NEAR(shading::smoothstep(0.5, 0.8, 0.65), 0.5, 1e-12);
}

TEST(Shading, IrradianceFollowsInverseSquareAndCosine) {
  Light l;
  l.position = {0.0f, 2.0f, 0.0f};
  l.intensity = 8.0f;
  glm::dvec3 dir;
  const glm::dvec3 e = shading::irradiance(l, glm::dvec3(0.0), glm::dvec3(0, 1, 0), dir);
  EXPECT_NEAR(e.r, 2.0, 1e-12);  // 8 cd / 2² · cos 0
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));
  EXPECT_NEAR(shading::irradiance(sun, glm::dvec3(5.0), glm::dvec3(0, 1, 0), dir).g,
              3.0 / std::sqrt(2.0), 1e-6);
}

// The packed cone (scale, offset) reproduces the smoothstep of the shading model.
TEST(Shading, LightPackLayoutMatchesTheShadingModel) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.0f, 2.0f, 3.0f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.range = 4.0f;
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.6f;
  spot.colour = {1.0f, 0.5f, 0.25f};
  spot.intensity = 2.0f;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0f, 0.0f, -1.0f};
  const PackedLights packed = packLights({spot, sun});
  EXPECT_EQ(packed.pointStart, 1);  // directional first
  EXPECT_EQ(packed.spotStart, 1);
  const auto& all = packed.texels;
  ASSERT_EQ(all.size(), 2u * layout::kFloatsPerLight);
  // The spot light is second: the directional one comes first.
  const std::vector<float> t(all.begin() + layout::kFloatsPerLight, all.end());
  EXPECT_EQ(t[0], 1.0f);
  EXPECT_FLOAT_EQ(t[3], 1.0f / 16.0f);
  EXPECT_EQ(t[8], 2.0f);
  EXPECT_EQ(t[10], 0.5f);
  for (double c : {0.7, 0.8, 0.85, 0.9, 0.95, 0.99}) {
    const double x = std::clamp(c * t[7] + t[11], 0.0, 1.0);
    EXPECT_NEAR(x * x * (3 - 2 * x), shading::smoothstep(std::cos(0.6), std::cos(0.3), c), 1e-5);
  }
  const float* d = &all[0];
  EXPECT_EQ(d[2], 1.0f);  // towards the light
  EXPECT_EQ(d[3], layout::kDirectionalMarker);
  EXPECT_EQ(d[7], 0.0f);
  EXPECT_EQ(d[11], 1.0f);
}

TEST(Shading, SrgbIsTheExactEncodingNotAPowerLaw) {
  EXPECT_EQ(encodeSrgb8(0.0), 0);
  EXPECT_EQ(encodeSrgb8(1.0), 255);
  EXPECT_EQ(encodeSrgb8(0.5), 188);      // a 2.2 power would give 186
  EXPECT_EQ(encodeSrgb8(0.0015654), 5);  // linear segment: 12.92 · x · 255 = 5.16
  EXPECT_EQ(encodeSrgb8(-1.0), 0);
  EXPECT_EQ(encodeSrgb8(std::nan("")), 0);
  for (int code = 0; code < 256; ++code) {
    EXPECT_EQ(encodeSrgb8(decodeSrgb8(std::uint8_t(code))), code);
  }
}

// encodeSrgb8 finds codes by comparisons (scene/srgb.cpp): against the curve in double, rounded,
// at two million values spread over [0, 1] in the exponent and in the value, at every float
// and double about each boundary between two codes, and at each float bucket's edges.
TEST(Shading, SrgbEncodingMatchesTheCurveEverywhere) {
  const auto curve = [](double x) {
    if (!(x > 0.0)) return 0;
    if (x >= 1.0) return 255;
    const double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    return int(std::lround(v * 255.0));
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-150.0, 0.0), value(0.0, 1.0);
  for (int i = 0; i < 1000000; ++i) {
    const double spread = std::ldexp(value(rng), int(exponent(rng))), even = value(rng);
    ASSERT_EQ(encodeSrgb8(spread), curve(spread)) << spread;
    ASSERT_EQ(encodeSrgb8(even), curve(even)) << even;
  }
  for (int code = 1; code < 256; ++code) {
    // Where the curve reaches code − ½, then the doubles and the floats on either side of it.
    const double v = (code - 0.5) / 255.0;
    const double at = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    double x = at;
    float f = float(at);
    for (int step = 0; step < 64; ++step) x = std::nextafter(x, 0.0), f = std::nextafter(f, 0.0f);
    for (int step = 0; step < 128; ++step) {
      ASSERT_EQ(encodeSrgb8(x), curve(x)) << x;
      ASSERT_EQ(encodeSrgb8(f), curve(f)) << f;
      x = std::nextafter(x, 1.0);
      f = std::nextafter(f, 1.0f);
    }
  }
  for (std::uint32_t bits = 0; bits <= 0x3f800000u; bits += 1u << 15) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    for (const double x :
         {double(f), std::nextafter(double(f), 0.0), std::nextafter(double(f), 1.0)})
      ASSERT_EQ(encodeSrgb8(x), curve(x)) << x;
  }
}

}  // namespace
}  // namespace manylight
