// The nodes and lights that scene/gltf_bulk.cpp reads with simdjson: what it hands tinygltf,
// that .gltf and .glb files load alike through it, and the exact one-line errors for nodes
// and lights that are not as glTF says (wrong types, indices out of range, non-finite values,
// broken JSON inside the arrays).
#include "scene/gltf_bulk.h"

#include <gtest/gtest.h>

#include <cstring>

#include "base/error.h"
#include "scene/gltf_loader.h"
#include "tests/test_support.h"

namespace manylight::testing {
namespace {

// A GLB of `json` alone (no binary chunk).
std::string glbOf(std::string json) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  auto word = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  return "glTF" + word(2) + word(std::uint32_t(20 + json.size())) +
         word(std::uint32_t(json.size())) + "JSON" + json;
}

gltf::SplitJson split(const std::string& json) {
  std::string padded = json + std::string(gltf::kJsonPadding, '\0');
  return gltf::splitJson(std::string_view(padded.data(), json.size()), padded.size());
}

// The document around `nodes` and `lights` (JSON array texts).
std::string document(const std::string& nodes, const std::string& lights) {
  return R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {"KHR_lights_punctual": {"lights": )" +
         lights + R"(}}, "nodes": )" + nodes + R"(, "scenes": [{"nodes": [0]}]})";
}

const char* const kPoint = R"([{"type": "point"}])";

TEST(GltfBulk, RestHasTheArraysEmptiedAndEverythingElseAsWritten) {
  const std::string json =
      R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0, "children": [1]}, {"camera": 0}],
  "extensions": {"KHR_lights_punctual": {"lights": [ {"type": "spot", "spot": {}} ] }, "X": 1}})";
  const gltf::SplitJson s = split(json);
  ASSERT_TRUE(s.parsed);
  EXPECT_EQ(s.rest, R"({"asset": {"version": "2.0"}, "nodes": [],
  "extensions": {"KHR_lights_punctual": {"lights": [] }, "X": 1}})");
  ASSERT_EQ(s.bulk.nodes.size(), 2u);
  EXPECT_EQ(s.bulk.nodes[0].mesh, 0);
  EXPECT_EQ(s.bulk.nodes[0].childCount, 1u);
  EXPECT_EQ(s.bulk.children[s.bulk.nodes[0].firstChild], 1);
  EXPECT_EQ(s.bulk.nodes[1].camera, 0);
  ASSERT_EQ(s.bulk.lights.size(), 1u);
  EXPECT_EQ(s.bulk.lights[0].type, gltf::PunctualType::Spot);
  EXPECT_EQ(s.bulk.lights[0].outerConeAngle, 0.7853981633974483);
}

TEST(GltfBulk, ReadsTransformsIndicesAndLightValues) {
  const gltf::SplitJson s = split(R"({"nodes": [
    {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 4,5,6,1], "translation": [9, 9, 9]},
    {"translation": [1, 2.5, -3e2], "rotation": [0, 0, 0, 1], "name": "a\u0041",
     "extensions": {"KHR_lights_punctual": {"light": 1.0}}, "extras": {"k": [null, true]}}],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "area"},
      {"type": "directional", "color": [0.5, 1, 2], "intensity": 3, "range": 4}]}}})");
  ASSERT_TRUE(s.parsed);
  ASSERT_EQ(s.bulk.nodes.size(), 2u);
  const gltf::NodeRecord& m = s.bulk.nodes[0];
  ASSERT_EQ(m.matrix, 0);
  EXPECT_EQ(m.trs, 0);  // a matrix wins over T, R, S
  EXPECT_EQ(s.bulk.matrices[0][12], 4.0);
  const gltf::NodeRecord& t = s.bulk.nodes[1];
  EXPECT_EQ(t.trs, gltf::NodeRecord::kTranslation | gltf::NodeRecord::kRotation);
  EXPECT_EQ(t.translation[2], -300.0);
  EXPECT_EQ(t.light, 1);
  ASSERT_EQ(s.bulk.lights.size(), 2u);
  EXPECT_EQ(s.bulk.lights[0].type, gltf::PunctualType::Other);
  EXPECT_EQ(s.bulk.otherTypes.at(0), "area");
  const gltf::LightRecord& d = s.bulk.lights[1];
  EXPECT_EQ(d.colorCount, 3u);
  EXPECT_EQ(d.color[0], 0.5);
  EXPECT_EQ(d.intensity, 3.0);
  EXPECT_EQ(d.range, 4.0);
}

// Scene roots as tinygltf read them: integers (wrapped to int) up to the first that is not
// one; a scene without a `nodes` array has none, and one that is not an object is tinygltf's.
TEST(GltfBulk, SceneRootsAreReadAsTinygltfReadThem) {
  const gltf::SplitJson s = split(R"({"scenes": [{"nodes": [2, 0, 4294967297, 1.5, 3],
    "name": "a"}, {"nodes": {"x": 1}}, {}, 7, {"nodes": [5], "nodes": [6, -1]}]})");
  ASSERT_TRUE(s.parsed);
  EXPECT_EQ(s.rest, R"({"scenes": [{"nodes": [],
    "name": "a"}, {"nodes": {"x": 1}}, {}, 7, {"nodes": [], "nodes": []}]})");
  ASSERT_EQ(s.bulk.sceneNodes.size(), 5u);
  EXPECT_EQ(s.bulk.sceneNodes[0], (std::vector<std::int32_t>{2, 0, 1}));
  EXPECT_TRUE(s.bulk.sceneNodes[1].empty());
  EXPECT_TRUE(s.bulk.sceneNodes[2].empty());
  EXPECT_TRUE(s.bulk.sceneNodes[3].empty());
  EXPECT_EQ(s.bulk.sceneNodes[4], (std::vector<std::int32_t>{6, -1}));
  EXPECT_FALSE(split(R"({"scenes": [{"nodes": [1, 2.]}]})").parsed);
}

// `count` nodes, each with light i, and `count` point lights of intensity i, as JSON arrays.
std::pair<std::string, std::string> manyNodesAndLights(int count) {
  std::string nodes = "[", lights = "[";
  for (int i = 0; i < count; ++i) {
    const std::string sep = i ? "," : "";
    nodes += sep + R"({"translation": [)" + std::to_string(i) +
             R"(, 0, 0], "extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(i) +
             "}}}";
    lights += sep + R"({"type": "point", "intensity": )" + std::to_string(i) + "}";
  }
  return {nodes + "]", lights + "]"};
}

// Past a megabyte each, nodes and lights are read on two threads: the same records, and of
// two faulty arrays the one earlier in the text is named, as a reader from the start would.
TEST(GltfBulk, LargeArraysReadOnTwoThreadsAsOnOne) {
  const int count = 40000;  // about 2.8 MB of nodes, 1.5 MB of lights
  auto [nodes, lights] = manyNodesAndLights(count);
  const gltf::SplitJson s = split(document(nodes, lights));
  ASSERT_TRUE(s.parsed);
  ASSERT_EQ(s.bulk.nodes.size(), std::size_t(count));
  ASSERT_EQ(s.bulk.lights.size(), std::size_t(count));
  for (int i = 0; i < count; i += 997) {
    EXPECT_EQ(s.bulk.nodes[std::size_t(i)].translation[0], double(i));
    EXPECT_EQ(s.bulk.nodes[std::size_t(i)].light, i);
    EXPECT_EQ(s.bulk.lights[std::size_t(i)].intensity, double(i));
  }
  nodes.insert(nodes.size() - 1, R"(, {"mesh": "x"})");
  lights.insert(lights.size() - 1, R"(, {"type": "point", "range": "x"})");
  const std::string lightError = "light " + std::to_string(count) + ": range is not a number";
  const std::string nodeError = "node " + std::to_string(count) + ": mesh is not an index";
  try {
    split(document(nodes, lights));  // the lights come first
    ADD_FAILURE() << "split";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), lightError);
  }
  const std::string nodesFirst = R"({"nodes": )" + nodes +
                                 R"(, "extensions": {"KHR_lights_punctual": {"lights": )" + lights +
                                 "}}}";
  try {
    split(nodesFirst);
    ADD_FAILURE() << "split";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), nodeError);
  }
}

// Bulk arrays are read in pieces of about 4 MB, on all cores: across their seams every record
// is its element's, children and matrices stay those of their nodes, and a fault in a later
// piece names its element's index in the whole array.
TEST(GltfBulk, AnArrayReadInPiecesGivesTheRecordsOfOneRead) {
  const int count = 70000;  // about 6 MB of nodes: two pieces
  std::string nodes = "[";
  for (int i = 0; i < count; ++i) {
    const std::string x = std::to_string(i);
    const std::string transform =
        i % 1000 == 7 ? R"("matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, )" + x + ", 0.5, 0, 1]"
                      : R"("translation": [)" + x + ", 0.5, 0]";
    nodes += std::string(i ? ",\n  " : "") + "{" + transform + R"(, "children": [)" +
             std::to_string((i + 1) % count) + "," + std::to_string((i + 2) % count) + "]}";
  }
  nodes += "]";
  const std::string lights = R"([{"type": "point"}])";
  const std::string nodesFirst = R"({"nodes": )" + nodes +
                                 R"(, "extensions": {"KHR_lights_punctual": {"lights": )" + lights +
                                 "}}}";
  const gltf::SplitJson s = split(nodesFirst);
  ASSERT_TRUE(s.parsed);
  ASSERT_EQ(s.bulk.nodes.size(), std::size_t(count));
  ASSERT_EQ(s.bulk.children.size(), std::size_t(2 * count));
  for (int i = 0; i < count; ++i) {
    const gltf::NodeRecord& n = s.bulk.nodes[std::size_t(i)];
    if (i % 1000 == 7) {
      ASSERT_GE(n.matrix, 0) << i;
      ASSERT_EQ(s.bulk.matrices[std::size_t(n.matrix)][12], double(i)) << i;
    } else {
      ASSERT_EQ(n.translation[0], double(i)) << i;
    }
    ASSERT_EQ(n.childCount, 2u) << i;
    ASSERT_EQ(*s.bulk.childrenBegin(n), (i + 1) % count) << i;
    ASSERT_EQ(*(s.bulk.childrenEnd(n) - 1), (i + 2) % count) << i;
  }
  ASSERT_EQ(s.bulk.matrices.size(), std::size_t(count / 1000));
  ASSERT_EQ(s.bulk.lights.size(), 1u);
  std::string faulty = nodesFirst;
  const std::string late = R"({"translation": [)" + std::to_string(count - 5) + ",";
  faulty.replace(faulty.find(late), late.size(), R"({"translation": ["x",)");
  try {
    split(faulty);
    ADD_FAILURE() << "split";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "node " + std::to_string(count - 5) + ": translation must be an array of 3 numbers");
  }
}

// Of two faults, the one earlier in the text is named, as a reader from the start would: a
// faulty node before a later key that is not an array, or before broken JSON.
TEST(GltfBulk, AFaultyElementIsNamedBeforeALaterFaultOfTheDocument) {
  for (const std::string later : {R"("nodes": 5})", R"("scenes": [})"}) {
    try {
      split(R"({"nodes": [{}, {"mesh": "x"}], )" + later + "}");
      ADD_FAILURE() << later;
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()), "node 1: mesh is not an index") << later;
    }
  }
}

// Keys are read as written: a `scenes` key written with escapes, which tinygltf would read,
// is refused in one line rather than shown without its roots.
TEST(GltfBulk, AnEscapedScenesKeyIsRefused) {
  const std::string path =
      writeFile("escaped-scenes.gltf",
                R"({"asset": {"version": "2.0"}, "nodes": [{}], "sc\u0065nes": [{"nodes": [0]}]})");
  EXPECT_EQ(loadError(path),
            path + ": scenes: written with escapes in its key, which is not supported");
}

TEST(GltfBulk, TextThatIsNotJsonIsLeftToTinygltf) {
  EXPECT_FALSE(split("{ this is not json").parsed);
  EXPECT_FALSE(split(R"({"nodes": [{"extras": {"a": 56.0f}}]})").parsed);
  EXPECT_FALSE(split(R"({"nodes": [{"name": "\uZZZZ"}]})").parsed);
  EXPECT_FALSE(split(R"({"nodes": [{"extras": {"\uh": 1}}]})").parsed);
  EXPECT_FALSE(split(R"({"nodes": [{"\uD800x": 1}]})").parsed);
  EXPECT_TRUE(split(R"({"nodes": [{"\uD83D\uDE00\n": 1, "extras": {"\u00e9": 1}}]})").parsed);
  EXPECT_FALSE(split(R"({"nodes": [{"translation": [1, 2, 3.]}]})").parsed);
  EXPECT_FALSE(split("[]").parsed);
}

TEST(GltfBulk, GltfAndGlbLoadTheSameLights) {
  RoomOptions o;
  o.lightCount = 12;
  const Scene text = loadGltf(roomScene(o, "bulk-room.gltf"));
  const Scene binary = loadGltf(roomScene(o, "bulk-room.glb"));
  ASSERT_EQ(text.lights.size(), 12u);
  ASSERT_EQ(binary.lights.size(), 12u);
  for (std::size_t i = 0; i < text.lights.size(); ++i) {
    EXPECT_EQ(text.lights[i].position, binary.lights[i].position) << i;
    EXPECT_EQ(text.lights[i].direction, binary.lights[i].direction) << i;
    EXPECT_EQ(text.lights[i].colour, binary.lights[i].colour) << i;
    EXPECT_EQ(text.lights[i].type, binary.lights[i].type) << i;
  }
  EXPECT_EQ(text.instances.size(), binary.instances.size());
  EXPECT_EQ(binary.meshes.size(), text.meshes.size());
}

TEST(GltfBulk, ByteOrderMarkIsSkipped) {
  const std::string json =
      document(R"([{"extensions": {"KHR_lights_punctual": {"light": 0}}}])", kPoint);
  const Scene s = loadGltf(writeFile("bom.gltf", "\xEF\xBB\xBF" + json));
  EXPECT_EQ(s.lights.size(), 1u);
}

struct BadInput {
  const char* name;
  std::string nodes, lights;
  const char* message;  // after "PATH: "
};

std::string lightNode(const std::string& index) {
  return R"([{"extensions": {"KHR_lights_punctual": {"light": )" + index + "}}}]";
}

const BadInput kBadInputs[] = {
    {"node-not-object", "[5]", kPoint, "node 0: not a JSON object"},
    {"translation-type", R"([{"translation": "x"}])", kPoint,
     "node 0: translation must be an array of 3 numbers"},
    {"translation-count", R"([{"translation": [1, 2]}])", kPoint,
     "node 0: translation must be an array of 3 numbers"},
    {"rotation-element", R"([{"rotation": [0, 0, "a", 1]}])", kPoint,
     "node 0: rotation must be an array of 4 numbers"},
    {"scale-count", R"([{"scale": [1, 1, 1, 1]}])", kPoint,
     "node 0: scale must be an array of 3 numbers"},
    {"matrix-count", R"([{"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0]}])", kPoint,
     "node 0: matrix must be an array of 16 numbers"},
    {"mesh-string", R"([{"mesh": "0"}])", kPoint, "node 0: mesh is not an index"},
    {"mesh-fraction", R"([{"mesh": 1.5}])", kPoint, "node 0: mesh is not an index"},
    {"camera-huge", R"([{"camera": 3e10}])", kPoint, "node 0: camera is not an index"},
    {"mesh-missing", R"([{"mesh": 4}])", kPoint, "mesh 4 does not exist"},
    {"mesh-negative", R"([{"mesh": -3}])", kPoint, "node 0: mesh -3 does not exist"},
    {"children-element", R"([{"children": [1, "x"]}, {}])", kPoint,
     "node 0: children must be an array of indices"},
    {"child-missing", R"([{"children": [7]}])", kPoint, "node 0: child 7 does not exist"},
    {"extensions-type", R"([{"extensions": []}])", kPoint, "node 0: extensions is not an object"},
    {"punctual-type", R"([{"extensions": {"KHR_lights_punctual": 1}}])", kPoint,
     "node 0: KHR_lights_punctual is not an object"},
    {"light-index-type", lightNode("\"a\""), kPoint,
     "node 0: KHR_lights_punctual.light is not an index"},
    {"light-index-missing", lightNode("3"), kPoint, "light 3 does not exist"},
    {"light-index-negative", lightNode("-2"), kPoint, "node 0: light -2 does not exist"},
    {"translation-infinite", R"([{"translation": [1e999, 0, 0]}])", kPoint,
     "node 0: transform is not finite"},
    {"scale-beyond-float", R"([{"scale": [1e39, 1, 1]}])", kPoint,
     "node 0: transform is not finite"},
    // A child of an infinite translation: ∞ · 0 in its world transform is NaN.
    {"child-of-infinite", R"([{"translation": [0, 0, 1e999], "children": [1]},
       {"rotation": [0, 1, 0, 0]}])",
     kPoint, "node 0: transform is not finite"},
    {"nodes-type", "{}", kPoint, "nodes is not an array"},
    {"lights-type", "[{}]", "{}", "KHR_lights_punctual.lights is not an array"},
    {"light-not-object", "[{}]", "[[]]", "light 0: not a JSON object"},
    {"light-no-type", "[{}]", "[{}]", "light 0: no type"},
    {"light-type-type", "[{}]", R"([{"type": 5}])", "light 0: type is not a string"},
    {"colour-type", "[{}]", R"([{"type": "point", "color": "red"}])",
     "light 0: color is not an array of numbers"},
    {"colour-count", "[{}]", R"([{"type": "point", "color": [1, 1]}])",
     "light 0: color must have 3 components, got 2"},
    {"intensity-type", "[{}]", R"([{"type": "point", "intensity": "1"}])",
     "light 0: intensity is not a number"},
    {"intensity-infinite", "[{}]", R"([{"type": "point", "intensity": -1e999}])",
     "light 0: colour and intensity must be finite and not negative"},
    {"range-negative", "[{}]", R"([{"type": "point", "range": -1}])",
     "light 0: range must be a positive number"},
    {"spot-missing", "[{}]", R"([{"type": "spot"}])",
     "light 0: a spot light without a spot object"},
    {"spot-type", "[{}]", R"([{"type": "spot", "spot": 3}])", "light 0: spot is not an object"},
    {"spot-angle-type", "[{}]", R"([{"type": "spot", "spot": {"outerConeAngle": "x"}}])",
     "light 0: spot.outerConeAngle is not a number"},
    {"second-light", "[{}]", R"([{"type": "point"}, {"type": "point", "color": [-1, 0, 0]}])",
     "light 1: colour and intensity must be finite and not negative"},
};

TEST(GltfBulk, BadNodesAndLightsNameTheElement) {
  for (const BadInput& b : kBadInputs) {
    const std::string json = document(b.nodes, b.lights);
    for (const char* ext : {".gltf", ".glb"}) {
      const std::string path =
          writeFile(std::string(b.name) + ext, std::string(ext) == ".glb" ? glbOf(json) : json);
      EXPECT_EQ(loadError(path), path + ": " + b.message);
    }
  }
}

TEST(GltfBulk, BrokenJsonInsideANodeIsRefusedAsBroken) {
  const std::string path =
      writeFile("broken-node.gltf", document(R"([{"extras": {"a": 56.0f}}])", kPoint));
  try {
    loadGltf(path);
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("syntax error while parsing object"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace manylight::testing
