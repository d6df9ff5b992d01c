#pragma once
// The shared cut's priority queue (cuts/cut_region.cpp): a max-heap of unique 64-bit keys.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace manylight::cut_heap {

// std::push_heap and std::pop_heap on a max-heap of unique keys, step for step as libstdc++
// does them (so the heap's layout, and with it the order of a cut's entries, is the same),
// with the larger child chosen without a branch: that choice is a coin toss, so a branch
// on it is mispredicted about half the time.

// Lets `value` rise from the hole at `hole` to its place (libstdc++'s __push_heap).
inline void siftUp(std::uint64_t* h, std::size_t hole, std::uint64_t value) {
  while (hole > 0) {
    const std::size_t parent = (hole - 1) / 2;
    if (!(h[parent] < value)) break;
    h[hole] = h[parent];
    hole = parent;
  }
  h[hole] = value;
}

inline void pushHeap(std::vector<std::uint64_t>& heap) {
  const std::size_t back = heap.size() - 1;
  siftUp(heap.data(), back, heap[back]);
}

// Moves the largest key to the back; the caller pops it.
inline void popHeap(std::vector<std::uint64_t>& heap) {
  std::uint64_t* h = heap.data();
  const std::size_t len = heap.size() - 1;  // the heap without its back
  const std::uint64_t value = h[len];
  h[len] = h[0];
  // The hole at the root sinks to a leaf along the larger children, then the old back
  // rises into it.
  std::size_t hole = 0, child = 0;
  while (len >= 2 && child < (len - 1) / 2) {
    child = 2 * (child + 1);
    child -= std::size_t(h[child] < h[child - 1]);
    h[hole] = h[child];
    hole = child;
  }
  if ((len & 1) == 0 && len >= 2 && child == (len - 2) / 2) {
    child = 2 * (child + 1);
    h[hole] = h[child - 1];
    hole = child - 1;
  }
  siftUp(h, hole, value);
}

}  // namespace manylight::cut_heap
