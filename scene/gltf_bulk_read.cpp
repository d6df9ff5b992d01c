#include "scene/gltf_bulk_read.h"

#include <array>
#include <cstring>

namespace manylight::gltf::bulk {

bool isJsonNumber(std::string_view t) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < t.size() && t[i] >= '0' && t[i] <= '9') ++i;
    return i > from;
  };
  if (i < t.size() && t[i] == '-') ++i;
  if (i < t.size() && t[i] == '0') {
    ++i;
  } else if (!digits()) {
    return false;
  }
  if (i < t.size() && t[i] == '.' && (++i, !digits())) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == t.size();
}

std::string str(std::size_t i) { return std::to_string(i); }

namespace {

bool isHex(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

// The code unit of the \uXXXX escape at `p` (just past the backslash); −1 when malformed.
long unit(const char* p) {
  if (p[0] != 'u' || !isHex(p[1]) || !isHex(p[2]) || !isHex(p[3]) || !isHex(p[4])) return -1;
  return std::strtol(std::string(p + 1, 4).c_str(), nullptr, 16);
}

// The length of the escape at `p` (just past the backslash), as JSON allows them (a high
// surrogate only with its low one); throws Syntax for a malformed one.
std::size_t escapeLength(const char* p) {
  if (std::strchr("\"\\/bfnrt", p[0]) != nullptr && p[0] != '\0') return 1;
  const long u = unit(p);
  if (u < 0 || (u >= 0xDC00 && u <= 0xDFFF)) throw Syntax{simdjson::STRING_ERROR};
  if (u < 0xD800 || u > 0xDBFF) return 5;
  const long low = p[5] == '\\' ? unit(p + 6) : -1;
  if (low < 0xDC00 || low > 0xDFFF) throw Syntax{simdjson::STRING_ERROR};
  return 11;
}

}  // namespace

std::string_view keyOf(simdjson::simdjson_result<od::field>& field) {
  od::raw_json_string raw;
  check(field.key().get(raw));
  const char* p = raw.raw();
  std::size_t n = 0;
  while (p[n] != '"') n += p[n] == '\\' ? 1 + escapeLength(p + n + 1) : 1;
  return {p, n};
}

void validate(od::value v, int depth) {
  od::json_type type;
  check(v.type().get(type));
  if (depth > 512) throw Syntax{simdjson::DEPTH_ERROR};
  switch (type) {
    case od::json_type::array: {
      od::array a;
      check(v.get_array().get(a));
      for (auto element : a) {
        od::value x;
        check(element.get(x));
        validate(x, depth + 1);
      }
      return;
    }
    case od::json_type::object: {
      od::object o;
      check(v.get_object().get(o));
      for (auto field : o) {
        keyOf(field);
        od::value x;
        check(field.value().get(x));
        validate(x, depth + 1);
      }
      return;
    }
    case od::json_type::number:
      number(v, [] { return std::string(); });
      return;
    case od::json_type::string: {
      std::string_view text;
      check(v.get_string().get(text));
      return;
    }
    case od::json_type::boolean: {
      bool b = false;
      check(v.get_bool().get(b));
      return;
    }
    case od::json_type::null: {
      bool null = false;
      check(v.is_null().get(null));
      if (!null) throw Syntax{simdjson::N_ATOM_ERROR};
      return;
    }
  }
}

namespace {

// The value of a node's KHR_lights_punctual extension.
void readNodeLight(od::value v, std::size_t i, NodeRecord& n) {
  od::object o;
  check(v.get_object().get(o),
        [&] { return "node " + str(i) + ": KHR_lights_punctual is not an object"; });
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value light;
    check(field.value().get(light));
    if (key != "light") {
      validate(light);
      continue;
    }
    n.light = index(
        light, [&] { return "node " + str(i) + ": KHR_lights_punctual.light is not an index"; });
  }
}

void readNodeExtensions(od::value v, std::size_t i, NodeRecord& n) {
  od::object o;
  check(v.get_object().get(o), [&] { return "node " + str(i) + ": extensions is not an object"; });
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value ext;
    check(field.value().get(ext));
    if (key == "KHR_lights_punctual") {
      readNodeLight(ext, i, n);
    } else {
      validate(ext);
    }
  }
}

void readChildren(od::value v, std::size_t i, NodeRecord& n, BulkArrays& out) {
  const auto message = [&] { return "node " + str(i) + ": children must be an array of indices"; };
  od::array a;
  check(v.get_array().get(a), message);
  n.firstChild = std::uint32_t(out.children.size());
  for (auto element : a) {
    od::value c;
    check(element.get(c));
    out.children.push_back(index(c, message));
  }
  n.childCount = std::uint32_t(out.children.size() - n.firstChild);
  if (n.childCount == 0) n.firstChild = 0;  // as for a node without children: pieces agree
}

}  // namespace

// A matrix wins over T, R, S, which glTF forbids beside it.
NodeRecord readNode(od::value v, std::size_t i, BulkArrays& out) {
  od::object o;
  check(v.get_object().get(o), [&] { return "node " + str(i) + ": not a JSON object"; });
  NodeRecord n;
  std::array<double, 16> matrix;
  bool hasMatrix = false;
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    const auto numbersOf = [&](std::size_t count) {
      return [&, count] {
        return "node " + str(i) + ": " + std::string(key) + " must be an array of " + str(count) +
               " numbers";
      };
    };
    if (key == "matrix") {
      exactNumbers(value, matrix.data(), 16, numbersOf(16));
      hasMatrix = true;
    } else if (key == "translation") {
      exactNumbers(value, n.translation, 3, numbersOf(3));
      n.trs |= NodeRecord::kTranslation;
    } else if (key == "rotation") {
      exactNumbers(value, n.rotation, 4, numbersOf(4));
      n.trs |= NodeRecord::kRotation;
    } else if (key == "scale") {
      exactNumbers(value, n.scale, 3, numbersOf(3));
      n.trs |= NodeRecord::kScale;
    } else if (key == "mesh" || key == "camera") {
      const std::int32_t x = index(
          value, [&] { return "node " + str(i) + ": " + std::string(key) + " is not an index"; });
      (key == "mesh" ? n.mesh : n.camera) = x;
    } else if (key == "children") {
      readChildren(value, i, n, out);
    } else if (key == "extensions") {
      readNodeExtensions(value, i, n);
    } else {
      validate(value);
    }
  }
  if (hasMatrix) {
    NodeRecord m;
    m.matrix = std::int32_t(out.matrices.size());
    m.mesh = n.mesh, m.camera = n.camera, m.light = n.light;
    m.firstChild = n.firstChild, m.childCount = n.childCount;
    n = m;
    out.matrices.push_back(matrix);
  }
  return n;
}

namespace {

void readSpot(od::value v, std::size_t i, LightRecord& l) {
  od::object o;
  check(v.get_object().get(o), [&] { return "light " + str(i) + ": spot is not an object"; });
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    if (key != "innerConeAngle" && key != "outerConeAngle") {
      validate(value);
      continue;
    }
    const double d = number(value, [&] {
      return "light " + str(i) + ": spot." + std::string(key) + " is not a number";
    });
    (key == "innerConeAngle" ? l.innerConeAngle : l.outerConeAngle) = d;
  }
}

PunctualType typeOf(std::string_view type) {
  if (type == "point") return PunctualType::Point;
  if (type == "spot") return PunctualType::Spot;
  if (type == "directional") return PunctualType::Directional;
  return PunctualType::Other;
}

}  // namespace

// A spot light needs its spot object, as tinygltf required.
LightRecord readLight(od::value v, std::size_t i, BulkArrays& out) {
  od::object o;
  check(v.get_object().get(o), [&] { return "light " + str(i) + ": not a JSON object"; });
  LightRecord l;
  bool hasType = false, hasSpot = false;
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    const auto notA = [&](const char* what) {
      return [&, what] { return "light " + str(i) + ": " + std::string(key) + " is not " + what; };
    };
    if (key == "type") {
      std::string_view type;
      check(value.get_string().get(type), notA("a string"));
      l.type = typeOf(type);
      if (l.type == PunctualType::Other) out.otherTypes[i] = std::string(type);
      hasType = true;
    } else if (key == "color") {
      l.colorCount = std::uint32_t(numbers(value, l.color, 3, notA("an array of numbers")));
    } else if (key == "intensity") {
      l.intensity = number(value, notA("a number"));
    } else if (key == "range") {
      l.range = number(value, notA("a number"));
    } else if (key == "spot") {
      readSpot(value, i, l);
      hasSpot = true;
    } else {
      validate(value);
    }
  }
  if (!hasType) throw SceneError("light " + str(i) + ": no type");
  if (l.type == PunctualType::Spot && !hasSpot)
    throw SceneError("light " + str(i) + ": a spot light without a spot object");
  return l;
}

bool isArray(od::value v) {
  od::json_type type;
  check(v.type().get(type));
  return type == od::json_type::array;
}

void readSceneNode(od::value x, std::vector<std::int32_t>& roots, bool& stopped) {
  if (!stopped) {
    std::int64_t i = 0;
    std::uint64_t u = 0;
    const simdjson::error_code e = x.get_int64().get(i);
    if (e == simdjson::SUCCESS) {
      roots.push_back(static_cast<std::int32_t>(i));
      return;
    }
    if (e == simdjson::NUMBER_OUT_OF_RANGE && x.get_uint64().get(u) == simdjson::SUCCESS) {
      roots.push_back(static_cast<std::int32_t>(u));
      return;
    }
    stopped = true;
  }
  validate(x);
}

}  // namespace manylight::gltf::bulk
