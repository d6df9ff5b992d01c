// The display transform of PNG output (image/display.h): tone maps and automatic exposure.
#include "image/display.h"

#include <gtest/gtest.h>

#include <cmath>

#include "image/image.h"

namespace manylight::testing {
namespace {

TEST(Display, ToneMapsStayInRangeAndKeepOrder) {
  for (const ToneMap t : {ToneMap::None, ToneMap::PbrNeutral, ToneMap::Aces}) {
    float previous = -1.0f;
    for (float x = 0.0f; x < 200.0f; x = x * 1.25f + 0.001f) {
      const glm::vec3 y = toneMap(t, glm::vec3(x));
      EXPECT_GE(y.r, 0.0f) << toneMapName(t) << " " << x;
      EXPECT_LE(y.r, 1.0f) << toneMapName(t) << " " << x;
      EXPECT_GE(y.r, previous) << toneMapName(t) << " " << x;
      EXPECT_NEAR(y.r, y.g, 1e-5f);  // greys stay grey (to rounding: ACES mixes channels)
      previous = y.r;
    }
  }
  EXPECT_EQ(toneMap(ToneMap::None, glm::vec3(0.3f, 2.0f, -1.0f)), glm::vec3(0.3f, 1.0f, 0.0f));
  // PBR Neutral: below its compression start only the 0.04 offset (and its quadratic toe).
  EXPECT_NEAR(toneMap(ToneMap::PbrNeutral, glm::vec3(0.5f)).r, 0.46f, 1e-6f);
  EXPECT_NEAR(toneMap(ToneMap::PbrNeutral, glm::vec3(0.04f)).r, 0.04f * 0.04f * 6.25f, 1e-7f);
  // ... and far above it, close to white without reaching it.
  EXPECT_GT(toneMap(ToneMap::PbrNeutral, glm::vec3(50.0f)).r, 0.99f);
  EXPECT_LT(toneMap(ToneMap::PbrNeutral, glm::vec3(2.0f)).r, 0.97f);
  // ACES (Hill's fit): its matrices keep greys grey, so 0.18 goes through the rational fit
  // alone: (0.18 (0.18 + 0.0245786) − 0.000090537) / (0.18 (0.983729 · 0.18 + 0.432951) +
  // 0.238081) = 0.10559.
  EXPECT_NEAR(toneMap(ToneMap::Aces, glm::vec3(0.18f)).r, 0.10559f, 1e-4f);
  EXPECT_EQ(parseToneMap("pbr-neutral"), ToneMap::PbrNeutral);
  EXPECT_THROW(parseToneMap("filmic"), Error);
}

Image flat(int covered, float value, int bright = 0, float brightValue = 0.0f) {
  Image im;
  im.width = covered + bright + 10;
  im.height = 1;
  im.rgba.assign(std::size_t(im.width) * 4, 0.0f);  // the last 10 pixels uncovered
  for (int i = 0; i < covered + bright; ++i) {
    const float v = i < covered ? value : brightValue;
    float* p = im.pixel(i, 0);
    p[0] = p[1] = p[2] = v;
    p[3] = 1.0f;
  }
  return im;
}

TEST(Display, AutoExposureBringsThe95thPercentileToTheKeyAndIgnoresAFewBrightPixels) {
  EXPECT_NEAR(autoExposure(flat(100, 0.2f)), std::log2(kAutoExposureKey / 0.2f), 1e-5f);
  // 3% of the pixels 500 times brighter (a bulb) change nothing.
  EXPECT_NEAR(autoExposure(flat(97, 0.2f, 3, 100.0f)), std::log2(kAutoExposureKey / 0.2f), 1e-5f);
  EXPECT_EQ(autoExposure(flat(0, 0.0f)), 0.0f);   // nothing covered
  EXPECT_EQ(autoExposure(flat(50, 0.0f)), 0.0f);  // all black
  EXPECT_EQ(autoExposure(flat(50, 1e-12f)), kAutoExposureLimit);
}

TEST(Display, PngCodesAreExposedToneMappedAndEncoded) {
  Image im = flat(1, 4.0f);
  const std::vector<std::uint8_t> plain = displayCodes(im, {});
  EXPECT_EQ(plain[0], 255);  // clamped
  const std::vector<std::uint8_t> mapped = displayCodes(im, {-1.0f, ToneMap::PbrNeutral});
  EXPECT_EQ(mapped[0], encodeSrgb8(toneMap(ToneMap::PbrNeutral, glm::vec3(2.0f)).r));
  EXPECT_EQ(mapped[3], 255);
  EXPECT_EQ(mapped[4 * 1 + 3], 0);  // uncovered
}

}  // namespace
}  // namespace manylight::testing
