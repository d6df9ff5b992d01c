#pragma once
// Runs work(0) … work(threads − 1) at once, work(0) on this thread, and once all have ended
// rethrows the first exception any of them threw (an exception may not leave a thread).
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace manylight {

template <typename Work>
void runOnThreads(int threads, const Work& work) {
  std::exception_ptr error;
  std::mutex mutex;
  auto guarded = [&](int index) {
    try {
      work(index);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (int index = 1; index < threads; ++index) pool.emplace_back(guarded, index);
  guarded(0);
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace manylight
