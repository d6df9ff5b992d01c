#pragma once
// A frame's cut texels (TileCuts' layout, 4 words each) as the pieces they were made in: the
// headers first, then the threads' entries in chunks, moved in rather than copied. They are
// copied once, into their destination (writeTo): the renderer writes them straight into the
// GL buffer it maps. Memory touched for the first time is the cost here, not the copying:
// on the 2-core test machine the first write to 64 MiB took 160 ms and the second 3 ms
// (page faults), and a 640×480 frame of 65,536 street spots (`--layout street`) at ε = 0.02 has 60
// MB of cut texels. Gathered into one vector before the upload, with each thread's entries grown by
// doubling, every word would be first touched four times instead of twice (the chunks here, the
// driver's buffer).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace manylight {

class CutTexels {
 public:
  // The headers and what else comes first; the pieces follow it.
  std::vector<std::uint32_t> head;

  // Appends `piece` (moved: its memory is kept, not copied).
  void append(std::vector<std::uint32_t>&& piece) {
    pieceWords_ += piece.size();
    if (!piece.empty()) pieces_.push_back(std::move(piece));
  }
  std::size_t words() const { return head.size() + pieceWords_; }
  std::size_t texels() const { return words() / 4; }
  bool empty() const { return words() == 0; }
  // Writes all words() words to `out`, in order.
  void writeTo(std::uint32_t* out) const {
    out = copyOut(head, out);
    for (const auto& p : pieces_) out = copyOut(p, out);
  }
  // All of them in one vector (tests, and the checks that read cuts back).
  std::vector<std::uint32_t> flat() const {
    std::vector<std::uint32_t> all(words());
    writeTo(all.data());
    return all;
  }
  // Moves the pieces (not the head) of `other` after these.
  void takePieces(CutTexels&& other) {
    for (auto& p : other.pieces_) append(std::move(p));
    other.pieces_.clear();
    other.pieceWords_ = 0;
  }

 private:
  static std::uint32_t* copyOut(const std::vector<std::uint32_t>& v, std::uint32_t* out) {
    return std::copy(v.begin(), v.end(), out);
  }
  std::vector<std::vector<std::uint32_t>> pieces_;
  std::size_t pieceWords_ = 0;
};

}  // namespace manylight
