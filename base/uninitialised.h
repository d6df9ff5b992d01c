#pragma once
// std::vector<T, Uninitialised<T>> sizes without writing its elements (resize, or a size
// given at construction, default-initialise them: nothing for a trivial T). For arrays of
// hundreds of megabytes at the light budget that are written whole right after they are
// sized: zeroing them first would cost a pass over memory and take every page fault on the
// thread that sizes them, instead of on the threads that fill them.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace manylight {

template <typename T>
struct Uninitialised : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = Uninitialised<U>;
  };
  Uninitialised() = default;
  template <typename U>
  Uninitialised(const Uninitialised<U>&) noexcept {}

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using UninitialisedVector = std::vector<T, Uninitialised<T>>;

}  // namespace manylight
