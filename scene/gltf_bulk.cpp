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

// The two arrays that grow with the light count.
enum class Bulk { Nodes, Lights };

// Arrays whose text is shorter than this are read on the calling thread.
constexpr std::size_t kThreadBytes = std::size_t(1) << 20;

// Empties `out`'s records of `kind` and makes room for `count` of them.
void restart(Bulk kind, std::size_t count, BulkArrays& out) {
  if (kind == Bulk::Nodes) {
    out.nodes.clear();
    out.children.clear();
    out.matrices.clear();
    out.nodes.reserve(count);
  } else {
    out.lights.clear();
    out.otherTypes.clear();
    out.lights.reserve(count);
  }
}

// Reads element i of an array of `kind` into `out`.
void readElement(Bulk kind, od::value x, std::size_t i, BulkArrays& out) {
  (kind == Bulk::Nodes ? readNode : readLight)(x, i, out);
}

// The first bulk array is read in pieces of about this much text, each copied between
// brackets into a buffer of its reader's own: its parser then indexes one piece, not the
// whole array again (the walk's index already covers it: a second index of the array would
// add a third to the loader's peak memory).
constexpr std::size_t kPieceBytes = std::size_t(4) << 20;

// An array as walkArray found it.
struct Walked {
  Span span;
  std::size_t count = 0;                // elements
  std::vector<std::size_t> pieceStart;  // per piece, the text offset of its first element
  std::vector<std::size_t> pieceFirst;  // and that element's index
};

// Walks the array `v` (one, or `what` is refused) element by element without reading them.
Walked walkArray(od::document& doc, od::value v, std::string_view json, const std::string& what) {
  const char* start = nullptr;
  check(v.current_location().get(start));
  od::array a;
  check(v.get_array().get(a), [&] { return what + " is not an array"; });
  Walked w;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    const char* at = nullptr;
    check(x.current_location().get(at));
    const std::size_t offset = std::size_t(at - json.data());
    if (w.count == 0 || offset - w.pieceStart.back() >= kPieceBytes) {
      w.pieceStart.push_back(offset);
      w.pieceFirst.push_back(w.count);
    }
    ++w.count;
  }
  w.span = {std::size_t(start - json.data()), arrayEnd(doc, json)};
  if (w.span.end <= w.span.begin || json[w.span.begin] != '[') throw Syntax{simdjson::TAPE_ERROR};
  return w;
}

// Reads the array walkArray walked, piece by piece, into `out`.
void readPieces(std::string_view json, const Walked& w, Bulk kind, BulkArrays& out) {
  restart(kind, w.count, out);
  od::parser parser;
  std::string piece;
  for (std::size_t j = 0; j < w.pieceStart.size(); ++j) {
    // The piece's elements: up to the next piece's separator, or to the array's ']'.
    std::size_t end = w.span.end - 1;
    if (j + 1 < w.pieceStart.size()) {
      end = w.pieceStart[j + 1];
      while (end > w.pieceStart[j] && json[end - 1] != ',') --end;
      --end;
    }
    piece.assign(1, '[');
    piece.append(json.substr(w.pieceStart[j], end - w.pieceStart[j]));
    piece += ']';
    const std::size_t length = piece.size();
    piece.append(simdjson::SIMDJSON_PADDING, ' ');
    od::document doc;
    check(parser.iterate(piece.data(), length, piece.size()).get(doc));
    od::array a;
    check(doc.get_array().get(a));
    std::size_t i = w.pieceFirst[j];
    for (auto element : a) {
      od::value x;
      check(element.get(x));
      readElement(kind, x, i++, out);
    }
  }
}

// The bulk arrays as the walk of the top level meets them. The first is walked past element
// by element (its pieces noted), then read in its pieces, on a thread of its own when large,
// started at once; every later one is read in place by the walk's parser, whose index already
// covers it. So the two are read at once (on the 1,048,576-light GLB the lights come first:
// the nodes, the larger, are read in place), and neither needs an index of its whole text
// besides the walk's. A later array of a kind replaces an earlier one's records, as for
// repeated keys.
class BulkReader {
 public:
  BulkReader(std::string_view json, BulkArrays& out) : json_(json), out_(out) {}

  // Reads the array `v` of `kind`, named `what` in errors; returns its span of the text.
  Span read(od::document& doc, od::value v, Bulk kind, const std::string& what) {
    if (met_) {
      replaced_ = replaced_ || (thread_.valid() && kind == threadKind_);
      return readArray(
          doc, v, json_, what, [&](std::size_t count) { restart(kind, count, out_); },
          [&](od::value x, std::size_t i) { readElement(kind, x, i, out_); });
    }
    met_ = true;
    const Walked walked = walkArray(doc, v, json_, what);
    if (walked.span.end - walked.span.begin < kThreadBytes) {
      readPieces(json_, walked, kind, out_);
      return walked.span;
    }
    threadKind_ = kind;
    thread_ = std::async(std::launch::async, [this, kind, walked] {
      try {
        readPieces(json_, walked, kind, threadOut_);
      } catch (...) {
        return std::current_exception();
      }
      return std::exception_ptr();
    });
    return walked.span;
  }

  // Waits for the thread and takes its records (unless a later array replaced them). Its
  // array comes before any other in the text: its error, if it had one, is the one a reader
  // from the start would meet first, and is thrown here.
  void finish() {
    if (!thread_.valid()) return;
    if (const std::exception_ptr error = thread_.get()) std::rethrow_exception(error);
    if (replaced_) return;
    if (threadKind_ == Bulk::Nodes) {
      out_.nodes = std::move(threadOut_.nodes);
      out_.children = std::move(threadOut_.children);
      out_.matrices = std::move(threadOut_.matrices);
    } else {
      out_.lights = std::move(threadOut_.lights);
      out_.otherTypes = std::move(threadOut_.otherTypes);
    }
  }

 private:
  std::string_view json_;
  BulkArrays& out_;
  bool met_ = false;       // the first bulk array has been met
  bool replaced_ = false;  // a later array of the thread's kind was read in place
  Bulk threadKind_ = Bulk::Nodes;
  BulkArrays threadOut_;
  std::future<std::exception_ptr> thread_;  // waits for its thread when destroyed
};

void readLightsExtension(od::document& doc, od::value v, BulkReader& bulk,
                         std::vector<Span>& spans) {
  od::object o;
  if (v.get_object().get(o) != simdjson::SUCCESS) return;  // tinygltf ignores it too
  for (auto field : o) {
    const std::string_view key = keyOf(field);
    if (key != "lights") continue;
    od::value lights;
    check(field.value().get(lights));
    spans.push_back(bulk.read(doc, lights, Bulk::Lights, "KHR_lights_punctual.lights"));
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

void readTopLevel(od::document& doc, std::string_view json, SplitJson& out, BulkReader& bulk,
                  std::vector<Span>& spans) {
  od::object top;
  check(doc.get_object().get(top));
  for (auto field : top) {
    const std::string_view key = keyOf(field);
    od::value value;
    check(field.value().get(value));
    if (key == "nodes") {
      spans.push_back(bulk.read(doc, value, Bulk::Nodes, "nodes"));
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
        readLightsExtension(doc, lights, bulk, spans);
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
    BulkReader bulk(json, out.bulk);
    try {
      od::parser parser;
      od::document doc;
      check(parser.iterate(json.data(), json.size(), capacity).get(doc));
      readTopLevel(doc, json, out, bulk, spans);
    } catch (...) {
      bulk.finish();  // the thread's error comes first in the text
      throw;
    }
    bulk.finish();
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
