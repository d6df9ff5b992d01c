#include "scene/gltf_bulk.h"

#include <simdjson.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "base/error.h"

namespace manylight::gltf {
namespace {

namespace od = simdjson::ondemand;
static_assert(kJsonPadding >= simdjson::SIMDJSON_PADDING);

// Text that is not JSON: left to tinygltf to name.
struct Syntax {
  simdjson::error_code code;
};

bool isTypeError(simdjson::error_code e) {
  return e == simdjson::INCORRECT_TYPE || e == simdjson::NUMBER_OUT_OF_RANGE;
}

// Throws SceneError(message()) when `e` says the value has the wrong type, Syntax when the
// text is broken. `message` is called only on failure.
template <typename F>
void check(simdjson::error_code e, const F& message) {
  if (e == simdjson::SUCCESS) return;
  if (isTypeError(e)) throw SceneError(message());
  throw Syntax{e};
}

void check(simdjson::error_code e) {
  if (e != simdjson::SUCCESS) throw Syntax{e};
}

// JSON's number grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
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

template <typename F>
double number(od::value v, const F& message) {
  double d = 0.0;
  const simdjson::error_code e = v.get_double().get(d);
  if (e == simdjson::NUMBER_ERROR) {
    // Beyond double's range: read as strtod reads it (±infinity, or 0), which the checks of
    // the values then refuse in their own words, as for any other non-finite value.
    std::string token(v.raw_json_token());
    while (!token.empty() && (token.back() == ' ' || token.back() == '\n' || token.back() == '\r' ||
                              token.back() == '\t'))
      token.pop_back();
    if (!isJsonNumber(token)) throw Syntax{e};
    return std::strtod(token.c_str(), nullptr);
  }
  check(e, message);
  return d;
}

// An array of numbers into out[0, capacity); returns how many the array holds.
template <typename F>
std::size_t numbers(od::value v, double* out, std::size_t capacity, const F& message) {
  od::array a;
  check(v.get_array().get(a), message);
  std::size_t n = 0;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    const double d = number(x, message);
    if (n < capacity) out[n] = d;
    ++n;
  }
  return n;
}

template <typename F>
void exactNumbers(od::value v, double* out, std::size_t count, const F& message) {
  if (numbers(v, out, count, message) != count) throw SceneError(message());
}

// An index: an integer (also written as 2.0) that fits an int; negative ones are kept for
// the checks that name them.
template <typename F>
std::int32_t index(od::value v, const F& message) {
  std::int64_t i = 0;
  simdjson::error_code e = v.get_int64().get(i);
  if (e == simdjson::INCORRECT_TYPE) {
    double d = 0.0;
    check(v.get_double().get(d), message);
    if (d != std::floor(d) || std::fabs(d) > 2147483647.0) throw SceneError(message());
    return std::int32_t(d);
  }
  check(e, message);
  if (i < std::numeric_limits<std::int32_t>::min() || i > std::numeric_limits<std::int32_t>::max())
    throw SceneError(message());
  return std::int32_t(i);
}

std::string str(std::size_t i) { return std::to_string(i); }

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

// A field's key as written between its quotes, read in place (its escapes checked): un-
// escaping every key would copy them all into the parser's string buffer, which grows with
// the document. A key written with escapes matches none of glTF's, and is read as an
// unknown property.
std::string_view keyOf(simdjson::simdjson_result<od::field>& field) {
  od::raw_json_string raw;
  check(field.key().get(raw));
  const char* p = raw.raw();
  std::size_t n = 0;
  while (p[n] != '"') n += p[n] == '\\' ? 1 + escapeLength(p + n + 1) : 1;
  return {p, n};
}

// Reads a value the loader does not use (a name, extras, another extension) to its end, so
// that broken JSON inside the arrays taken from tinygltf is still refused as broken.
void validate(od::value v, int depth = 0) {
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
}

// Node `i`. A matrix wins over T, R, S, which glTF forbids beside it.
void readNode(od::value v, std::size_t i, BulkArrays& out) {
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
  out.nodes.push_back(n);
}

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

// Light `i`. A spot light needs its spot object, as tinygltf required.
void readLight(od::value v, std::size_t i, BulkArrays& out) {
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
  out.lights.push_back(l);
}

bool isArray(od::value v) {
  od::json_type type;
  check(v.type().get(type));
  return type == od::json_type::array;
}

// Where the array just read ends: one past its ']', found back from the next token.
std::size_t arrayEnd(od::document& doc, std::string_view json) {
  const char* next = nullptr;
  check(doc.current_location().get(next));
  std::size_t end = std::size_t(next - json.data());
  while (end > 0 && json[end - 1] != ']') --end;
  return end;
}

struct Span {
  std::size_t begin, end;
};

// Reads the array `v` element by element; `reserve` is told the count first.
template <typename Reserve, typename Read>
Span readArray(od::document& doc, od::value v, std::string_view json, const std::string& what,
               const Reserve& reserve, const Read& read) {
  const char* start = nullptr;
  check(v.current_location().get(start));
  od::array a;
  check(v.get_array().get(a), [&] { return what + " is not an array"; });
  std::size_t count = 0;
  check(a.count_elements().get(count));
  reserve(count);
  std::size_t i = 0;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    read(x, i++);
  }
  const Span s{std::size_t(start - json.data()), arrayEnd(doc, json)};
  if (s.end <= s.begin || json[s.begin] != '[') throw Syntax{simdjson::TAPE_ERROR};
  return s;
}

void readLightsExtension(od::document& doc, od::value v, std::string_view json, SplitJson& out,
                         std::vector<Span>& spans) {
  od::object o;
  if (v.get_object().get(o) != simdjson::SUCCESS) return;  // tinygltf ignores it too
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    if (key != "lights") continue;
    od::value lights;
    check(field.value().get(lights));
    out.bulk.lights.clear();
    out.bulk.otherTypes.clear();
    spans.push_back(readArray(
        doc, lights, json, "KHR_lights_punctual.lights",
        [&](std::size_t n) { out.bulk.lights.reserve(n); },
        [&](od::value x, std::size_t i) { readLight(x, i, out.bulk); }));
  }
}

// A root of a scene, as tinygltf's integer arrays take one: a JSON integer, cast to int.
// After the first value that is not one, tinygltf keeps none; `stopped` says so.
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

// The scene `v`: its `nodes` array read into `roots` (and emptied in the rest), the rest of
// it left to tinygltf, which also refuses a scene that is not an object.
void readScene(od::document& doc, od::value v, std::string_view json,
               std::vector<std::int32_t>& roots, std::vector<Span>& spans) {
  od::json_type type;
  check(v.type().get(type));
  if (type != od::json_type::object) return validate(v);
  od::object o;
  check(v.get_object().get(o));
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    check(value.type().get(type));
    if (key != "nodes" || type != od::json_type::array) {
      if (key == "nodes") roots.clear();
      validate(value);
      continue;
    }
    roots.clear();
    bool stopped = false;
    spans.push_back(readArray(
        doc, value, json, "scene nodes", [&](std::size_t n) { roots.reserve(n); },
        [&](od::value x, std::size_t) { readSceneNode(x, roots, stopped); }));
  }
}

void readTopLevel(od::document& doc, std::string_view json, SplitJson& out,
                  std::vector<Span>& spans) {
  od::object top;
  check(doc.get_object().get(top));
  for (auto field : top) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    if (key == "nodes") {
      out.bulk.nodes.clear();
      out.bulk.children.clear();
      out.bulk.matrices.clear();
      spans.push_back(readArray(
          doc, value, json, "nodes", [&](std::size_t n) { out.bulk.nodes.reserve(n); },
          [&](od::value x, std::size_t i) { readNode(x, i, out.bulk); }));
    } else if (key == "scenes" && isArray(value)) {
      out.bulk.sceneNodes.clear();
      od::array scenes;
      check(value.get_array().get(scenes));
      for (auto element : scenes) {
        od::value scene;
        check(element.get(scene));
        out.bulk.sceneNodes.emplace_back();
        readScene(doc, scene, json, out.bulk.sceneNodes.back(), spans);
      }
    } else if (key == "extensions") {
      od::object extensions;
      if (value.get_object().get(extensions) != simdjson::SUCCESS) continue;
      for (auto ext : extensions) {
        const std::string_view name = keyOf(ext);
        if (name != "KHR_lights_punctual") continue;
        od::value lights;
        check(ext.value().get(lights));
        readLightsExtension(doc, lights, json, out, spans);
      }
    }
  }
}

}  // namespace

SplitJson splitJson(std::string_view text, std::size_t capacity) {
  // A UTF-8 byte order mark, which glTF forbids and tinygltf skips, is kept for tinygltf.
  const std::string_view bom = text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(0, 3) : "";
  const std::string_view json = text.substr(bom.size());
  capacity -= bom.size();
  SplitJson out;
  std::vector<Span> spans;
  try {
    od::parser parser;
    od::document doc;
    check(parser.iterate(json.data(), json.size(), capacity).get(doc));
    readTopLevel(doc, json, out, spans);
  } catch (const Syntax& s) {
    SplitJson failed;
    failed.syntaxError = simdjson::error_message(s.code);
    return failed;
  }
  out.parsed = true;
  std::size_t size = json.size();
  for (const Span& s : spans) size -= s.end - s.begin - 2;
  out.rest.reserve(bom.size() + size);
  out.rest.append(bom);
  std::size_t at = 0;
  for (const Span& s : spans) {
    out.rest.append(json.substr(at, s.begin - at));
    out.rest.append("[]");
    at = s.end;
  }
  out.rest.append(json.substr(at));
  return out;
}

}  // namespace manylight::gltf
