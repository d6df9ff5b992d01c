// Colour fidelity without GL: the power-law fit (bake/colour_fit.h) and the compact node
// colour codings (bake/node_colour.h).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "bake/colour_fit.h"
#include "bake/node_colour.h"
#include "scene/srgb.h"
#include "tests/test_support.h"

namespace manylight {
namespace {

using testing::testFolder;
using testing::writeFile;

TEST(Colour, PowerFitTheUe4TableGivesItsGamma) {
  // The Lightcuts-in-UE4 work's measured pairs: 8-bit code in, point-light brightness out.
  const std::vector<FitPair> pairs = {{255, 5000}, {216, 3470}, {171, 2076}, {123, 1005},
                                      {85, 445},   {76, 349},   {59, 200}};
  const PowerFit fit = fitPowerLaw(pairs);
  EXPECT_NEAR(fit.gamma, 2.1996, 0.0005);
  EXPECT_NEAR(fit.a, 0.025430, 0.000005);
  EXPECT_NEAR(fit.log10A, std::log10(fit.a), 1e-12);
  EXPECT_GT(fit.r2, 0.9999);
  EXPECT_LT(fit.worstRelative, 0.01);
}

TEST(Colour, PowerFitAnExactPowerLawIsRecovered) {
  std::vector<FitPair> pairs;
  for (double x : {0.5, 1.0, 3.0, 10.0, 70.0}) pairs.push_back({x, 3.5 * std::pow(x, 1.7)});
  const PowerFit fit = fitPowerLaw(pairs);
  EXPECT_NEAR(fit.gamma, 1.7, 1e-12);
  EXPECT_NEAR(fit.a, 3.5, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  EXPECT_LT(fit.worstRelative, 1e-12);
}

TEST(Colour, PowerFitUnfittableInputIsRefused) {
  auto message = [](const std::vector<FitPair>& pairs) {
    try {
      fitPowerLaw(pairs);
    } catch (const BakeError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message({{2, 3}, {2, 4}}), "a power-law fit needs at least two different inputs");
  EXPECT_EQ(message({{0, 3}, {2, 4}}),
            "cannot fit the pair (0.000000, 3.000000): both values must be finite and > 0");
  const std::string path = writeFile("pairs.csv", "in,out\n1,2\n3,x\n");
  try {
    readFitPairs(path);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":3: expected two numbers, got '3,x'");
  }
}

// Colours spanning twelve orders of magnitude and every hue, as tree nodes have them.
std::vector<glm::vec3> nodeLikeColours() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> colours;
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.0f, -6.0f + 12.0f * u(rng));
    colours.push_back(scale * glm::vec3(u(rng), u(rng), u(rng)));
  }
  colours.push_back(glm::vec3(0.0f, 0.0f, 1e-30f));  // far below RGB9_E5's range
  return colours;
}

TEST(Colour, NodeColourEveryCodingStaysWithinItsSlack) {
  const auto colours = nodeLikeColours();
  for (NodeColourCoding coding : {NodeColourCoding::Rgb9e5, NodeColourCoding::Fitted}) {
    const NodeColourCoder coder(coding, colours);
    for (const glm::vec3& c : colours) {
      const glm::vec3 d = coder.decode(coder.encode(c));
      const double largest = std::max(d.r, std::max(d.g, d.b));
      EXPECT_GT(largest, 0.0) << "a light is never lost";
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(std::abs(double(d[k]) - c[k]), coder.slack * largest + coder.slackFloor)
            << int(coding);
      }
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(coder.p99Error[k], coder.maxError[k]);
      EXPECT_GT(coder.maxError[k], 0.0);
    }
  }
}

TEST(Colour, NodeColourRgb9e5IsTheMoreAccurate) {
  // Measured on node-like colours: 9-bit mantissas round to within 1/512 of the largest
  // channel; 8-bit codes on a γ ≈ 2.2 curve to within about γ/(2·186) in the top octave.
  const auto colours = nodeLikeColours();
  const NodeColourCoder rgb9e5(NodeColourCoding::Rgb9e5, colours),
      fitted(NodeColourCoding::Fitted, colours);
  EXPECT_LT(rgb9e5.slack, 0.0021);
  EXPECT_LT(fitted.slack, 0.0075);
  EXPECT_LT(rgb9e5.slack, fitted.slack);
  EXPECT_GT(rgb9e5.slackFloor, 0.0);  // the dimmest colours fall back on the floor
  EXPECT_EQ(fitted.slackFloor, 0.0);
  EXPECT_FALSE(fitted.fittedToSrgb());
  EXPECT_GT(fitted.fit().gamma, 1.5);
  EXPECT_LT(fitted.fit().gamma, 2.6);
}

TEST(Colour, NodeColourGreyScenesFitTheSrgbCurve) {
  const NodeColourCoder coder(NodeColourCoding::Fitted, {glm::vec3(2.0f), glm::vec3(0.5f)});
  EXPECT_TRUE(coder.fittedToSrgb());
  EXPECT_EQ(coder.fit().pairs, 255u);
  EXPECT_EQ(coder.decode(coder.encode(glm::vec3(0.0f))), glm::vec3(0.0f));
}

}  // namespace
}  // namespace manylight
