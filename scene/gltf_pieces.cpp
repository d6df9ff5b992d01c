#include "scene/gltf_pieces.h"

#include <algorithm>
#include <utility>

namespace manylight::gltf::bulk {
namespace {

// Reads `piece` of `array` into its records, with `parser` and `buffer` of the calling
// thread's own; keeps the first error instead of throwing it.
void readPiece(std::string_view json, BulkArray& array, Piece& piece, od::parser& parser,
               std::string& buffer) {
  try {
    buffer.assign(1, '[');
    buffer.append(json.substr(piece.begin, piece.end - piece.begin));
    buffer += ']';
    const std::size_t length = buffer.size();
    buffer.append(simdjson::SIMDJSON_PADDING, ' ');
    od::document doc;
    check(parser.iterate(buffer.data(), length, buffer.size()).get(doc));
    od::array a;
    check(doc.get_array().get(a));
    const std::size_t end = piece.first + piece.count;
    std::size_t i = piece.first;
    for (auto element : a) {
      od::value x;
      check(element.get(x));
      if (i == end) throw Syntax{simdjson::TAPE_ERROR};  // not the elements the walk passed
      if (array.kind == Bulk::Nodes) {
        array.records.nodes[i] = readNode(x, i, piece.side);
      } else {
        array.records.lights[i] = readLight(x, i, piece.side);
      }
      ++i;
    }
    if (i != end) throw Syntax{simdjson::TAPE_ERROR};
  } catch (...) {
    piece.error = std::current_exception();
  }
}

// Moves `array`'s records into `out`, its pieces' children and matrices appended in order
// (each node's firstChild and matrix moved past the earlier pieces').
void take(BulkArray& array, BulkArrays& out) {
  if (array.kind == Bulk::Lights) {
    out.lights = std::move(array.records.lights);
    out.otherTypes.clear();
    for (Piece& p : array.pieces) out.otherTypes.merge(p.side.otherTypes);
    return;
  }
  out.nodes = std::move(array.records.nodes);
  out.children.clear();
  out.matrices.clear();
  for (const Piece& p : array.pieces) {
    const std::size_t children = out.children.size(), matrices = out.matrices.size();
    if (children > 0 || matrices > 0) {
      for (std::size_t i = p.first; i < p.first + p.count; ++i) {
        NodeRecord& n = out.nodes[i];
        if (n.childCount > 0) n.firstChild += std::uint32_t(children);
        if (n.matrix >= 0) n.matrix += std::int32_t(matrices);
      }
    }
    out.children.insert(out.children.end(), p.side.children.begin(), p.side.children.end());
    out.matrices.insert(out.matrices.end(), p.side.matrices.begin(), p.side.matrices.end());
  }
}

}  // namespace

std::size_t arrayEnd(od::document& doc, std::string_view json) {
  const char* next = nullptr;
  check(doc.current_location().get(next));
  std::size_t end = std::size_t(next - json.data());
  while (end > 0 && json[end - 1] != ']') --end;
  return end;
}

BulkArray walkArray(od::document& doc, od::value v, std::string_view json, Bulk kind,
                    const std::string& what) {
  const char* start = nullptr;
  check(v.current_location().get(start));
  od::array a;
  check(v.get_array().get(a), [&] { return what + " is not an array"; });
  BulkArray array;
  array.kind = kind;
  std::size_t count = 0;
  for (auto element : a) {
    od::value x;
    check(element.get(x));
    const char* at = nullptr;
    check(x.current_location().get(at));
    const std::size_t offset = std::size_t(at - json.data());
    if (count == 0 || offset - array.pieces.back().begin >= kPieceBytes) {
      array.pieces.emplace_back();
      array.pieces.back().begin = offset;
      array.pieces.back().first = count;
    }
    ++count;
  }
  array.begin = std::size_t(start - json.data());
  array.end = arrayEnd(doc, json);
  if (array.end <= array.begin || json[array.begin] != '[') throw Syntax{simdjson::TAPE_ERROR};
  // A piece's text ends before the separator of the next piece's first element, the last
  // one's before the array's ']'.
  for (std::size_t j = 0; j < array.pieces.size(); ++j) {
    Piece& p = array.pieces[j];
    const bool last = j + 1 == array.pieces.size();
    p.count = (last ? count : array.pieces[j + 1].first) - p.first;
    p.end = last ? array.end - 1 : array.pieces[j + 1].begin;
    if (!last) {
      while (p.end > p.begin && json[p.end - 1] != ',') --p.end;
      --p.end;
    }
  }
  if (kind == Bulk::Nodes) {
    array.records.nodes.resize(count);
  } else {
    array.records.lights.resize(count);
  }
  return array;
}

PieceReader::~PieceReader() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    closed_ = stopped_ = true;
  }
  queued_.notify_all();
  for (std::thread& t : pool_) t.join();
}

void PieceReader::add(BulkArray array) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    arrays_.push_back(std::move(array));
    BulkArray& a = arrays_.back();
    for (Piece& p : a.pieces) {
      tasks_.push_back({&a, &p});
      waitingBytes_ += p.end - p.begin;
    }
    if (!poolTried_ && waitingBytes_ >= kThreadBytes) startPool();
  }
  queued_.notify_all();
}

void PieceReader::startPool() {
  poolTried_ = true;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned readers = std::clamp(cores, 2u, kMaxReaders);
  try {
    for (unsigned k = 1; k < readers; ++k) pool_.emplace_back([this] { work(); });
  } catch (const std::exception&) {
    // No more threads (a process or memory limit): the caller reads the rest in finish().
  }
}

void PieceReader::work() {
  od::parser parser;
  std::string buffer;
  for (;;) {
    Task task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      queued_.wait(lock, [&] { return stopped_ || next_ < tasks_.size() || closed_; });
      if (stopped_ || next_ == tasks_.size()) return;
      task = tasks_[next_++];
    }
    readPiece(json_, *task.array, *task.piece, parser, buffer);
  }
}

void PieceReader::finish(BulkArrays& out) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  queued_.notify_all();
  work();
  for (std::thread& t : pool_) t.join();
  pool_.clear();
  for (BulkArray& a : arrays_) {
    for (const Piece& p : a.pieces) {
      if (p.error) std::rethrow_exception(p.error);
    }
  }
  BulkArray* last[2] = {nullptr, nullptr};
  for (BulkArray& a : arrays_) last[int(a.kind)] = &a;
  for (BulkArray* a : last) {
    if (a) take(*a, out);
  }
}

}  // namespace manylight::gltf::bulk
