#pragma once
// Runs work(0) … work(threads − 1) at once, work(0) on this thread (and any whose thread
// could not be started, after it), and once all have ended rethrows the first exception any
// of them threw (an exception may not leave a thread).
// runOnShares cuts a range of items into consecutive shares, one a thread.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <future>
#include <mutex>
#include <thread>
#include <vector>

namespace manylight {

// std::async's policy for work that should run on a thread of its own but may run deferred
// (on the thread that waits for it) where no thread can be started, a process or memory
// limit: libstdc++ then falls back to deferring instead of throwing std::system_error.
inline constexpr std::launch kThreadOrDeferred = std::launch::async | std::launch::deferred;

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
  int started = 1;  // work(0) is this thread's
  try {
    pool.reserve(std::size_t(std::max(threads - 1, 0)));
    for (; started < threads; ++started) pool.emplace_back(guarded, started);
  } catch (const std::exception&) {
    // No more threads (a process or memory limit): this thread does the rest in turn.
  }
  guarded(0);
  for (int index = started; index < threads; ++index) guarded(index);
  for (std::thread& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

// How many shares runOnShares cuts `count` items into: one a hardware thread, but none of
// fewer than `minShare` items (thread start-up would cost more than it saves).
inline int sharesOf(std::size_t count, std::size_t minShare) {
  const std::size_t hardware = std::max(1u, std::thread::hardware_concurrency());
  return int(std::clamp(count / std::max<std::size_t>(minShare, 1), std::size_t(1), hardware));
}

// Runs work(k, from, to) for share k of `shares` over items [0, count), at once.
template <typename Work>
void runOnShares(int shares, std::size_t count, const Work& work) {
  runOnThreads(shares, [&](int k) {
    work(k, count * std::size_t(k) / std::size_t(shares),
         count * std::size_t(k + 1) / std::size_t(shares));
  });
}

}  // namespace manylight
