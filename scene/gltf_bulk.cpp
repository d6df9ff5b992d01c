#include "scene/gltf_bulk.h"

#include <cstring>
#include <exception>
#include <future>

#include "scene/gltf_bulk_read.h"

namespace manylight::gltf {
namespace {

using namespace bulk;
static_assert(kJsonPadding >= simdjson::SIMDJSON_PADDING);

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

// The two arrays that grow with the light count, read after the rest of the document, each
// by a parser of its own: at once, on two threads, when both are large.
enum class Bulk { Nodes, Lights };

struct Deferred {
  Bulk kind;
  Span span;
};

// Arrays whose text is shorter than this are read on the calling thread.
constexpr std::size_t kThreadBytes = std::size_t(1) << 20;

// The array `v`, checked to be one, skipped; its span is read later.
Span deferArray(od::value v, std::string_view json, const std::string& what) {
  od::array a;
  check(v.get_array().get(a), [&] { return what + " is not an array"; });
  std::string_view raw;
  check(a.raw_json().get(raw));
  const std::size_t begin = std::size_t(raw.data() - json.data());
  std::size_t end = begin + raw.size();
  while (end > begin && json[end - 1] != ']') --end;  // the view runs to the next token
  if (end <= begin || json[begin] != '[') throw Syntax{simdjson::TAPE_ERROR};
  return {begin, end};
}

// Reads the array at `span` of `json` (padded to `capacity`) with a parser of its own.
void readDeferred(std::string_view json, std::size_t capacity, const Deferred& d, BulkArrays& out) {
  od::parser parser;
  od::document doc;
  check(
      parser.iterate(json.data() + d.span.begin, d.span.end - d.span.begin, capacity - d.span.begin)
          .get(doc));
  od::array a;
  check(doc.get_array().get(a));
  const auto reserve = [&](std::size_t count) {
    if (d.kind == Bulk::Nodes) {
      out.nodes.clear();
      out.children.clear();
      out.matrices.clear();
      out.nodes.reserve(count);
    } else {
      out.lights.clear();
      out.otherTypes.clear();
      out.lights.reserve(count);
    }
  };
  readElements(a, reserve, [&](od::value x, std::size_t i) {
    (d.kind == Bulk::Nodes ? readNode : readLight)(x, i, out);
  });
}

// The deferred arrays of one kind, in order (a later one replaces an earlier one's records,
// as for repeated keys); the offset of the first that failed, and why, if one did.
struct KindOutcome {
  std::size_t failedAt = 0;
  std::exception_ptr error;
};

KindOutcome readKind(std::string_view json, std::size_t capacity,
                     const std::vector<Deferred>& deferred, Bulk kind, BulkArrays& out) {
  for (const Deferred& d : deferred) {
    if (d.kind != kind) continue;
    try {
      readDeferred(json, capacity, d, out);
    } catch (...) {
      return {d.span.begin, std::current_exception()};
    }
  }
  return {};
}

// Reads every deferred array into `out`; throws what the first failing one (in the text's
// order) threw, as one reading the text from the start would have.
void readAllDeferred(std::string_view json, std::size_t capacity,
                     const std::vector<Deferred>& deferred, BulkArrays& out) {
  std::size_t bytes[2] = {0, 0};
  for (const Deferred& d : deferred) bytes[int(d.kind)] += d.span.end - d.span.begin;
  BulkArrays lights;  // the lights' records, apart while two threads fill them
  std::future<KindOutcome> second;
  if (bytes[0] >= kThreadBytes && bytes[1] >= kThreadBytes) {
    second = std::async(std::launch::async,
                        [&] { return readKind(json, capacity, deferred, Bulk::Lights, lights); });
  }
  KindOutcome outcomes[2];
  outcomes[0] = readKind(json, capacity, deferred, Bulk::Nodes, out);
  if (second.valid()) {
    outcomes[1] = second.get();
    out.lights = std::move(lights.lights);
    out.otherTypes = std::move(lights.otherTypes);
  } else {
    outcomes[1] = readKind(json, capacity, deferred, Bulk::Lights, out);
  }
  const KindOutcome* first = nullptr;
  for (const KindOutcome& o : outcomes) {
    if (o.error && (!first || o.failedAt < first->failedAt)) first = &o;
  }
  if (first) std::rethrow_exception(first->error);
}

void readLightsExtension(od::value v, std::string_view json, std::vector<Deferred>& deferred,
                         std::vector<Span>& spans) {
  od::object o;
  if (v.get_object().get(o) != simdjson::SUCCESS) return;  // tinygltf ignores it too
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    if (key != "lights") continue;
    od::value lights;
    check(field.value().get(lights));
    spans.push_back(deferArray(lights, json, "KHR_lights_punctual.lights"));
    deferred.push_back({Bulk::Lights, spans.back()});
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

void readTopLevel(od::document& doc, std::string_view json, SplitJson& out,
                  std::vector<Deferred>& deferred, std::vector<Span>& spans) {
  od::object top;
  check(doc.get_object().get(top));
  for (auto field : top) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    if (key == "nodes") {
      spans.push_back(deferArray(value, json, "nodes"));
      deferred.push_back({Bulk::Nodes, spans.back()});
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
        readLightsExtension(lights, json, deferred, spans);
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
  std::vector<Deferred> deferred;
  try {
    {
      // This parser's index (4 bytes a token) is freed before the deferred arrays' own.
      od::parser parser;
      od::document doc;
      check(parser.iterate(json.data(), json.size(), capacity).get(doc));
      readTopLevel(doc, json, out, deferred, spans);
    }
    readAllDeferred(json, capacity, deferred, out.bulk);
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
