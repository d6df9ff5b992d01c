#pragma once
// The bulk arrays of scene/gltf_bulk.cpp (nodes, lights) read in pieces by a pool of
// threads while the walk of the document's top level goes on. Internal to scene/.
//
// The walk passes each bulk array element by element without reading it, noting where its
// pieces of about kPieceBytes of text begin; the pieces are read at once by the pool, each
// copied between brackets into its reader's own buffer, so that a parser indexes one piece
// (the walk's index of the whole text is freed when the walk ends, before the records are
// all read). Every element is read as one reader from the start of the text would read it:
// the same records, and of the faulty elements the first in the text is named.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "scene/gltf_bulk_read.h"

namespace manylight::gltf::bulk {

enum class Bulk { Nodes, Lights };

// Text of a bulk array per piece.
constexpr std::size_t kPieceBytes = std::size_t(4) << 20;
// Pieces are read on the calling thread alone until this much text waits.
constexpr std::size_t kThreadBytes = std::size_t(1) << 20;
// Threads reading pieces at most, the caller's included: each holds a piece's copy and index
// (about 6 MB), and more than a few share the memory's bandwidth.
constexpr unsigned kMaxReaders = 8;

// Consecutive elements of a bulk array.
struct Piece {
  std::size_t begin = 0, end = 0;    // the elements' text, without the separators around it
  std::size_t first = 0, count = 0;  // the index of its first element; its elements
  BulkArrays side;                   // its nodes' children and matrices, its lights' other types
  std::exception_ptr error;          // what stopped its reading, if anything did
};

// A bulk array as the walk passed it; `records` holds one node or light per element.
struct BulkArray {
  Bulk kind = Bulk::Nodes;
  std::size_t begin = 0, end = 0;  // its text, brackets included
  std::vector<Piece> pieces;
  BulkArrays records;
};

// Where the array just passed ends: one past its ']', found back from the next token.
std::size_t arrayEnd(od::document& doc, std::string_view json);

// Passes the array `v` of `kind` (refused as `what` when it is no array) element by element
// without reading them; its records sized for its elements.
BulkArray walkArray(od::document& doc, od::value v, std::string_view json, Bulk kind,
                    const std::string& what);

class PieceReader {
 public:
  explicit PieceReader(std::string_view json) : json_(json) {}
  PieceReader(const PieceReader&) = delete;
  PieceReader& operator=(const PieceReader&) = delete;
  ~PieceReader();  // stops the pool (pieces not yet taken are left unread)

  // Queues the pieces of `array`, the next bulk array in the text; the pool starts once
  // kThreadBytes of text wait, with a thread for each core but the caller's (at least one,
  // kMaxReaders − 1 at most).
  void add(BulkArray array);
  // Reads the pieces left on this thread too, then waits for the pool. Throws the error of
  // the first faulty piece in the text's order; else moves the records of the last array of
  // each kind into `out` (a later array replaces an earlier one's, as for repeated keys).
  void finish(BulkArrays& out);

 private:
  struct Task {
    BulkArray* array;
    Piece* piece;
  };
  void work();  // reads queued pieces until none is left and the queue is closed
  void startPool();

  std::string_view json_;
  std::deque<BulkArray> arrays_;  // a deque: queued tasks keep pointing at their arrays
  std::mutex mutex_;
  std::condition_variable queued_;
  std::vector<Task> tasks_;
  std::size_t next_ = 0;          // the next task to take
  std::size_t waitingBytes_ = 0;  // text queued before the pool started
  bool closed_ = false;           // no more tasks will come
  bool stopped_ = false;          // take no more tasks
  bool poolTried_ = false;        // startPool ran (it may have started no thread)
  std::vector<std::thread> pool_;
};

}  // namespace manylight::gltf::bulk
