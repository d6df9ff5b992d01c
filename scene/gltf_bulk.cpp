#include "scene/gltf_bulk.h"

#include <cstring>
#include <exception>

#include "scene/gltf_bulk_read.h"
#include "scene/gltf_pieces.h"

namespace manylight::gltf {
namespace {

using namespace bulk;
static_assert(kJsonPadding >= simdjson::SIMDJSON_PADDING);

struct Span {
  std::size_t begin, end;
};

// Reads the array `a` element by element; `reserve` is told the count first.
template <typename Reserve, typename Read>
void readElements(od::array& a, const Reserve& reserve, const Read& read) {
  std::size_t count = 0;
  check(a.count_elements().get(count));
  reserve(count);
  std::size_t i = 0;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    read(x, i++);
  }
}

// Reads the array `v` element by element (readElements); returns its span of `json`.
template <typename Reserve, typename Read>
Span readArray(od::document& doc, od::value v, std::string_view json, const std::string& what,
               const Reserve& reserve, const Read& read) {
  const char* start = nullptr;
  check(v.current_location().get(start));
  od::array a;
  check(v.get_array().get(a), [&] { return what + " is not an array"; });
  readElements(a, reserve, read);
  const Span s{std::size_t(start - json.data()), arrayEnd(doc, json)};
  if (s.end <= s.begin || json[s.begin] != '[') throw Syntax{simdjson::TAPE_ERROR};
  return s;
}

// Passes the bulk array `v` of `kind` (bulk.add queues it to be read); returns its span.
Span passBulk(od::document& doc, od::value v, std::string_view json, Bulk kind,
              const std::string& what, PieceReader& bulk) {
  BulkArray array = walkArray(doc, v, json, kind, what);
  const Span span{array.begin, array.end};
  bulk.add(std::move(array));
  return span;
}

void readLightsExtension(od::document& doc, od::value v, std::string_view json, PieceReader& bulk,
                         std::vector<Span>& spans) {
  od::object o;
  if (v.get_object().get(o) != simdjson::SUCCESS) return;  // tinygltf ignores it too
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    if (key != "lights") continue;
    od::value lights;
    check(field.value().get(lights));
    spans.push_back(passBulk(doc, lights, json, Bulk::Lights, "KHR_lights_punctual.lights", bulk));
  }
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

void readTopLevel(od::document& doc, std::string_view json, SplitJson& out, PieceReader& bulk,
                  std::vector<Span>& spans) {
  od::object top;
  check(doc.get_object().get(top));
  for (auto field : top) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    if (key == "nodes") {
      spans.push_back(passBulk(doc, value, json, Bulk::Nodes, "nodes", bulk));
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
        readLightsExtension(doc, lights, json, bulk, spans);
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
    PieceReader bulk(json);
    try {
      // The walk's parser (its index, 4 bytes a token of the whole text) is freed before the
      // walk's thread joins the pool.
      od::parser parser;
      od::document doc;
      check(parser.iterate(json.data(), json.size(), capacity).get(doc));
      readTopLevel(doc, json, out, bulk, spans);
    } catch (...) {
      bulk.finish(out.bulk);  // a faulty piece comes before where the walk failed
      throw;
    }
    bulk.finish(out.bulk);
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
