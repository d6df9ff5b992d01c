// The benchmark sweep's inputs and figures without GL: the light layouts and the image
// error measures (image/image_errors.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "base/error.h"
#include "generators/light_layouts.h"
#include "image/image_errors.h"

namespace manylight::testing {
namespace {

TEST(BenchTools, LightLayoutsEveryLayoutGivesItsCountDeterministicallyAndFinite) {
  for (const auto& [layout, name] : lightLayoutNames()) {
    EXPECT_EQ(parseLightLayout(name), layout);
    EXPECT_EQ(lightLayoutName(layout), name);
    for (int n : {1, 2, 3, 1025}) {
      const std::vector<Light> a = layoutLights(layout, n, 7), b = layoutLights(layout, n, 7);
      ASSERT_EQ(a.size(), std::size_t(n)) << name;
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(a[i].position, b[i].position) << name;
        EXPECT_EQ(a[i].intensity, b[i].intensity) << name;
        EXPECT_TRUE(std::isfinite(a[i].intensity) && a[i].intensity > 0.0f) << name << " " << i;
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(a[i].position[c])) << name;
      }
    }
  }
}

TEST(BenchTools, LightLayoutsUnknownNameIsRefusedWithTheChoices) {
  try {
    parseLightLayout("spiral");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown light layout 'spiral' (choose from uniform, clustered, street, mixed, "
              "coincident, two-groups, wide-intensities, bright-among-dim, far, spots-away, "
              "on-surfaces, eight-bit-colours, uniform-ranged, street-ranged)");
  }
}

TEST(BenchTools, LightLayoutsAdversarialLayoutsAreWhatTheySay) {
  const auto bright = layoutLights(LightLayout::BrightAmongDim, 1000, 7);
  double dim = 0.0;
  for (std::size_t i = 1; i < bright.size(); ++i) dim += bright[i].intensity;
  EXPECT_NEAR(bright[0].intensity, dim, 1e-3 * dim);  // as bright as all the others together
  for (const Light& l : layoutLights(LightLayout::SpotsAway, 500, 7)) {
    EXPECT_EQ(l.type, LightType::Spot);
    // Facing up, cone included: nothing below the light is ever lit.
    EXPECT_GT(std::acos(l.direction.y), 0.0f);
    EXPECT_LT(std::acos(l.direction.y) + l.outerConeAngle, 1.5707963f);
  }
  for (const Light& l : layoutLights(LightLayout::Street, 100, 7)) {
    EXPECT_EQ(l.type, LightType::Spot);
    EXPECT_EQ(l.direction, glm::vec3(0.0f, -1.0f, 0.0f));
    EXPECT_NEAR(l.position.y, 4.0f, 0.01f);
  }
  for (const Light& l : layoutLights(LightLayout::Far, 100, 7))
    EXPECT_GT(glm::length(l.position), 0.99e5f);
  const auto coincident = layoutLights(LightLayout::Coincident, 10, 7);
  for (const Light& l : coincident) EXPECT_EQ(l.position, coincident[0].position);
}

Image image(int w, int h, float value) {
  Image i;
  i.width = w;
  i.height = h;
  i.rgba.assign(std::size_t(w) * h * 4, value);
  return i;
}

TEST(BenchTools, ImageErrorsEqualImagesHaveNoError) {
  const Image a = image(4, 3, 0.5f);
  const ImageErrors e = measureErrors(a, a);
  EXPECT_EQ(e.pixels, 12);
  EXPECT_EQ(e.maxRelative, 0.0);
  EXPECT_EQ(e.rmse8, 0.0);
  EXPECT_TRUE(std::isinf(e.psnr8));
  EXPECT_EQ(e.offByMoreThanOneCode, 0.0);
}

TEST(BenchTools, ImageErrorsFiguresCoverCoveredPixelsOfTheChosenRows) {
  Image ref = image(4, 2, 0.5f), img = ref;
  ref.pixel(3, 1)[3] = 0.0f;  // background: never compared
  img.pixel(3, 1)[0] = 100.0f;
  // One pixel 10% too bright in every channel: 0.5 encodes as code 188, 0.55 as 196.
  for (int c = 0; c < 3; ++c) img.pixel(1, 0)[c] = 0.55f;
  ImageErrors e = measureErrors(img, ref);
  EXPECT_EQ(e.pixels, 7);
  EXPECT_NEAR(e.maxRelative, 0.1, 1e-6);
  EXPECT_NEAR(e.maxAbsolute, 0.05, 1e-6);
  EXPECT_NEAR(e.p99Relative, 0.1, 1e-6);  // the 99th percentile of 7 values is the largest
  // Pixels, not values: one pixel with three channels off counts once.
  EXPECT_NEAR(e.offByMoreThanOneCode, 1.0 / 7.0, 1e-12);
  // RMSE over the 7·3 values of which 3 differ by 8 codes: sqrt(3·(8/255)²/21).
  EXPECT_NEAR(e.rmse8, std::sqrt(3.0 * 64.0 / (255.0 * 255.0) / 21.0), 1e-6);
  EXPECT_NEAR(e.psnr8, 20.0 * std::log10(1.0 / e.rmse8), 1e-3);

  e = measureErrors(img, ref, {false, true});  // row 1 only
  EXPECT_EQ(e.pixels, 3);
  EXPECT_EQ(e.maxRelative, 0.0);
}

TEST(BenchTools, ImageErrorsNaNAndBlackReferencesReadAsLargeErrors) {
  Image ref = image(2, 1, 0.0f), img = ref;
  ref.pixel(0, 0)[3] = ref.pixel(1, 0)[3] = 1.0f;
  img.pixel(0, 0)[1] = std::nanf("");
  img.pixel(1, 0)[2] = 1e-3f;  // should be black
  const ImageErrors e = measureErrors(img, ref);
  EXPECT_EQ(e.nonFinite, 1);
  EXPECT_TRUE(std::isinf(e.maxRelative));
  EXPECT_TRUE(std::isinf(e.maxAbsolute));
  img.pixel(0, 0)[1] = 0.0f;
  const ImageErrors black = measureErrors(img, ref);
  EXPECT_EQ(black.nonFinite, 0);
  EXPECT_NEAR(black.maxRelative, 1e-3 / kRelativeErrorFloor, 1e-3);  // the floor divides
  Image other = image(3, 1, 0.0f);
  EXPECT_THROW(measureErrors(other, ref), ImageError);
}

TEST(BenchTools, RelativeErrorsSortThePixelsTheReferenceCoversAndFindTheLargest) {
  Image ref = image(3, 2, 0.5f), img = ref;
  ref.pixel(2, 1)[3] = 0.0f;  // background: never compared
  img.pixel(2, 1)[0] = 100.0f;
  img.pixel(1, 0)[1] = 0.6f;   // 0.1 off a largest channel of 0.5: 20%
  img.pixel(0, 1)[2] = 0.45f;  // 10%
  const RelativeErrors e = relativeErrors(img, ref);
  ASSERT_EQ(e.sorted.size(), 5u);
  EXPECT_NEAR(e.sorted.back(), 0.2, 1e-6);
  EXPECT_NEAR(e.sorted[3], 0.1, 1e-6);
  EXPECT_EQ(e.sorted[2], 0.0);
  EXPECT_EQ(e.maxX, 1);
  EXPECT_EQ(e.maxY, 0);
  // The p-th percentile of 5 values is the ⌈5p/100⌉-th smallest.
  EXPECT_EQ(percentileOf(e.sorted, 100.0), e.sorted[4]);
  EXPECT_EQ(percentileOf(e.sorted, 80.0), e.sorted[3]);
  EXPECT_EQ(percentileOf(e.sorted, 79.0), e.sorted[3]);
  EXPECT_EQ(percentileOf(e.sorted, 60.0), e.sorted[2]);
  EXPECT_EQ(percentileOf(e.sorted, 1e-6), e.sorted[0]);
  EXPECT_EQ(percentileOf({}, 50.0), 0.0);
  // A NaN channel is infinitely wrong, not equal.
  img.pixel(0, 0)[0] = std::nanf("");
  EXPECT_TRUE(std::isinf(relativeErrors(img, ref).sorted.back()));
  EXPECT_THROW(relativeErrors(image(2, 2, 0.5f), ref), ImageError);
}

}  // namespace
}  // namespace manylight::testing
