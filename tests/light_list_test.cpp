// Light lists without GL (scene/light_list.h): the three formats, their optional columns, the
// errors, the light budget, and 8-bit sRGB colours summed linearly in the light tree.
#include "scene/light_list.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "bake/light_tree.h"
#include "scene/srgb.h"
#include "tests/test_support.h"

namespace manylight {
namespace {

using testing::testFolder;
using testing::writeFile;

std::vector<Light> readList(const std::string& path, std::size_t budget = 1000) {
  Scene scene;
  LoadOptions options;
  options.lightBudget = budget;
  appendLightList(path, scene, options);
  return scene.lights;
}

std::string listError(const std::string& path, std::size_t budget = 1000) {
  try {
    readList(path, budget);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

// The UE4 work's example line, and the same light in the other two formats.
const char* kDumpLine =
    "GUID C2C14DFC4DDFAFF43D562F8AE934C28C - Position X=-300.000 Y=0.000 Z=150.000 W=1.000 - "
    "Radius 250 - "
    "Color (R=255,G=76,B=216,A=0) - Brightness = 5000\n";

void expectTheExampleLight(const Light& l) {
  EXPECT_EQ(l.type, LightType::Point);
  EXPECT_EQ(l.position, glm::vec3(-300.0f, 0.0f, 150.0f));
  EXPECT_EQ(l.range, 250.0f);
  EXPECT_EQ(l.intensity, 5000.0f);
  // Decoded with the exact sRGB curve, not a 2.2 power: code 76 is 0.0723, not 0.0705.
  EXPECT_EQ(l.colour.r, 1.0f);
  EXPECT_FLOAT_EQ(l.colour.g, float(decodeSrgb8(76)));
  EXPECT_NEAR(l.colour.g, 0.072272, 1e-6);
  EXPECT_FLOAT_EQ(l.colour.b, float(decodeSrgb8(216)));
}

TEST(LightList, TheThreeFormatsGiveTheSameLight) {
  const auto dump =
      readList(writeFile("lights.txt", std::string("# exported from UE4\n\n") + kDumpLine));
  const auto csv = readList(writeFile("lights.csv",
                                      "x,y,z,r,g,b,brightness,radius,falloff\n"
                                      "-300,0,150,255,76,216,5000,250,inverse-square\n"));
  const auto json = readList(writeFile(
      "lights.json",
      R"({"lights": [{"position": [-300, 0, 150], "color": [255, 76, 216], "brightness": 5000,
                     "radius": 250, "falloff": "inverse-square"}]})"));
  for (const auto* lights : {&dump, &csv, &json}) {
    ASSERT_EQ(lights->size(), 1u);
    expectTheExampleLight(lights->front());
  }
}

TEST(LightList, OptionalColumnsAndKeys) {
  // Columns in any order, radius and falloff optional (no radius: infinite range).
  const auto csv =
      readList(writeFile("any-order.csv", "brightness,b,g,r,z,y,x\n2,0,0,255,3,2,1\n"));
  ASSERT_EQ(csv.size(), 1u);
  EXPECT_EQ(csv[0].position, glm::vec3(1, 2, 3));
  EXPECT_EQ(csv[0].colour, glm::vec3(1, 0, 0));
  EXPECT_EQ(csv[0].range, 0.0f);
  const auto json = readList(
      writeFile("array.json", R"([{"position": [1, 2, 3], "color": [0, 0, 0], "brightness": 0}])"));
  ASSERT_EQ(json.size(), 1u);
  EXPECT_EQ(json[0].colour, glm::vec3(0.0f));
}

struct BadList {
  const char* name;
  const char* text;
  const char* message;  // after "PATH"
};

const BadList kBadLists[] = {
    {"short.txt",
     "GUID AB - Position X=1 Y=2 Z=3 - Radius 250 - Color (R=1,G=2,B=3) - Brightness = 5\nGUID AB "
     "- Position X=1 Y=2\n",
     ":2: expected 'Z=', got the end of the line"},
    {"word.txt",
     "\n\nGUID AB - Position X=1 Y=2 Z=3 - Radius 250 - Color (R=1,G=2,B=3) - Brightness = lots\n",
     ":3: expected a number for Brightness, got 'lots'"},
    {"code.txt",
     "GUID AB - Position X=1 Y=2 Z=3 - Radius 250 - Color (R=256,G=2,B=3) - Brightness = 5\n",
     ":1: colour R must be an integer code 0..255, got 256.000000"},
    {"radius.txt",
     "GUID AB - Position X=1 Y=2 Z=3 - Radius 0 - Color (R=1,G=2,B=3) - Brightness = 5\n",
     ":1: radius must be > 0"},
    {"tail.txt",
     "GUID AB - Position X=1 Y=2 Z=3 - Radius 1 - Color (R=1,G=2,B=3) - Brightness = 5 extra\n",
     ":1: expected the end of the line, got 'extra'"},
    {"nan.csv", "x,y,z,r,g,b,brightness\n0,0,0,1,1,1,1\n0,nan,0,1,1,1,1\n",
     ":3: y: expected a number, got 'nan'"},
    {"fields.csv", "x,y,z,r,g,b,brightness\n0,0,0,1,1,1\n", ":2: expected 7 fields, got 6"},
    {"header.csv", "x,y,z,r,g,b\n",
     ":1: the header has no column 'brightness'; expected "
     "x,y,z,r,g,b,brightness[,radius][,falloff]"},
    {"column.csv", "x,y,z,r,g,b,brightness,colour\n",
     ":1: unknown column 'colour'; expected x,y,z,r,g,b,brightness[,radius][,falloff]"},
    {"falloff.csv", "x,y,z,r,g,b,brightness,falloff\n0,0,0,1,1,1,1,exponent-8\n",
     ":2: falloff 'exponent-8' is not modelled; only inverse-square (glTF's) is"},
    {"fraction.csv", "x,y,z,r,g,b,brightness\n0,0,0,0.5,1,1,1\n",
     ":2: colour R must be an integer code 0..255, got 0.500000"},
    {"negative.csv", "x,y,z,r,g,b,brightness\n0,0,0,1,1,1,-1\n",
     ":2: brightness must be a finite number >= 0, got -1.000000"},
    {"syntax.json", "[{\"position\": [1, 2, 3],\n \"color\": }]",
     ": parse error at line 2, column 11: syntax error while parsing value - unexpected '}'; "
     "expected '[', '{', or a literal"},
    {"key.json", R"([{"position": [1, 2, 3], "color": [1, 2, 3], "brightness": 1, "radious": 3}])",
     ": light 0: unknown key 'radious'; expected position, color, brightness, radius, falloff"},
    {"missing.json", R"({"lights": [{"position": [1, 2, 3], "brightness": 1}]})",
     ": light 0: no color"},
    {"object.json", R"({"light": []})", ": expected an array of lights or {\"lights\": [...]}"},
};

TEST(LightList, MalformedListsNameTheLine) {
  for (const BadList& b : kBadLists) {
    const std::string path = writeFile(b.name, b.text);
    EXPECT_EQ(listError(path), path + b.message) << b.name;
  }
}

TEST(LightList, FilesThatCannotBeListsAreRefused) {
  const std::string missing = (testFolder() / "none.csv").string();
  EXPECT_EQ(listError(missing), missing + ": cannot open: No such file or directory");
  EXPECT_EQ(listError(testFolder().string()), testFolder().string() + ": not a regular file");
}

TEST(LightList, TheBudgetCountsTheSceneAndTheList) {
  std::string text = "x,y,z,r,g,b,brightness\n";
  for (int i = 0; i < 5; ++i) text += "0,0,0,1,1,1,1\n";
  const std::string path = writeFile("five.csv", text);
  EXPECT_EQ(readList(path, 5).size(), 5u);
  Scene scene;
  scene.lights.resize(2);
  LoadOptions options;
  options.lightBudget = 6;
  try {
    appendLightList(path, scene, options);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": 5 lights and the scene's 2 exceed the light budget of 6 (--light-budget)");
  }
  EXPECT_EQ(scene.lights.size(), 2u) << "nothing added";
}

TEST(LightList, ClusterColoursAreSumsOfLinearColours) {
  // Two lights of one cluster, 8-bit colours from a list. The tree's root holds the sum of
  // their exact linear colours; summing the encoded codes first (then decoding, as a
  // renderer working in sRGB would) gives a visibly different, wrong colour.
  const auto lights = readList(
      writeFile("two.csv", "x,y,z,r,g,b,brightness\n0,0,0,200,40,10,1\n1,0,0,10,40,200,1\n"));
  const LightTree tree = buildLightTrees(lights)[0];
  const glm::vec3 root = tree.nodes[0].intensity;
  for (int c = 0; c < 3; ++c) {
    const int a = c == 0 ? 200 : c == 1 ? 40 : 10, b = c == 0 ? 10 : c == 1 ? 40 : 200;
    const double right = decodeSrgb8(std::uint8_t(a)) + decodeSrgb8(std::uint8_t(b));
    EXPECT_NEAR(root[c], right, 1e-6 * right) << "channel " << c;
    // Encoded average, decoded, times two lights: what summing encoded values gives.
    const double wrong = 2.0 * decodeSrgb8(std::uint8_t((a + b) / 2));
    if (a != b) {
      EXPECT_GT(std::abs(wrong - right), 0.2 * right) << "channel " << c;
    }
  }
}

}  // namespace
}  // namespace manylight
