#pragma once
// Runs work(0) … work(threads − 1) at once, on this thread alone when there is one.
#include <thread>
#include <vector>

namespace manylight {

template <typename Work>
void onThreads(int threads, const Work& work) {
  if (threads <= 1) {
    work(0);
    return;
  }
  std::vector<std::thread> pool;
  for (int index = 0; index < threads; ++index) pool.emplace_back(work, index);
  for (std::thread& th : pool) th.join();
}

}  // namespace manylight
