#pragma once
// The arrays of a glTF document that grow with its light count, `nodes`, KHR_lights_punctual's
// `lights` and each scene's `nodes`, read with simdjson's on-demand parser straight into
// compact records (no document tree), and the rest of the JSON, with those arrays emptied,
// for tinygltf. The loader takes nodes, lights and scene roots only from here, whatever the
// file's size.
// Internal to scene/.
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace manylight::gltf {

// A node as the loader uses it. glTF defaults where the file gives nothing.
struct NodeRecord {
  enum : std::uint8_t { kTranslation = 1, kRotation = 2, kScale = 4 };
  double translation[3] = {0.0, 0.0, 0.0};
  double rotation[4] = {0.0, 0.0, 0.0, 1.0};  // quaternion xyzw
  double scale[3] = {1.0, 1.0, 1.0};
  std::int32_t matrix = -1;  // index into BulkArrays::matrices; −1: the node has T, R, S
  std::int32_t mesh = -1, camera = -1;
  std::int32_t light = -1;                       // KHR_lights_punctual.light; −1: none
  std::uint32_t firstChild = 0, childCount = 0;  // a range of BulkArrays::children
  std::uint8_t trs = 0;                          // which of T, R, S the file gives
};

enum class PunctualType : std::uint8_t { Point, Spot, Directional, Other };

// A KHR_lights_punctual light, its values as the file gives them (checked by Converter).
struct LightRecord {
  PunctualType type = PunctualType::Point;
  std::uint32_t colorCount = 0;  // components the file gives; 0: none (white)
  double color[3] = {1.0, 1.0, 1.0};
  double intensity = 1.0;
  double range = 0.0;  // 0: infinite
  double innerConeAngle = 0.0, outerConeAngle = 0.7853981633974483;
};

struct BulkArrays {
  std::vector<NodeRecord> nodes;
  std::vector<std::int32_t> children;
  std::vector<std::array<double, 16>> matrices;  // column-major, as in the file
  std::vector<LightRecord> lights;
  std::map<std::size_t, std::string> otherTypes;  // the type of each PunctualType::Other light
  // Per element of `scenes`, its root nodes as tinygltf reads them: JSON integers up to the
  // first that is not one (a scene that is no object, or has no array there: none).
  std::vector<std::vector<std::int32_t>> sceneNodes;

  // The children of `node`.
  const std::int32_t* childrenBegin(const NodeRecord& n) const {
    return children.data() + n.firstChild;
  }
  const std::int32_t* childrenEnd(const NodeRecord& n) const {
    return children.data() + n.firstChild + n.childCount;
  }
};

// What splitJson found.
struct SplitJson {
  bool parsed = false;      // false: the text is not a JSON object simdjson could read
  std::string syntaxError;  // simdjson's reason when not parsed
  BulkArrays bulk;
  std::string rest;  // the JSON with those arrays emptied; "" when not parsed
};

// Reads `json` (whose buffer holds at least `capacity` ≥ json.size() + 64 readable bytes
// from json.data()). Throws SceneError for a node or light that is not as glTF says, naming
// it ("node 3: translation must be an array of 3 numbers"); returns parsed = false for text
// that is not JSON, so that tinygltf names the syntax error as it always has.
SplitJson splitJson(std::string_view json, std::size_t capacity);

// Bytes of readable padding splitJson wants after the JSON.
constexpr std::size_t kJsonPadding = 64;

}  // namespace manylight::gltf
