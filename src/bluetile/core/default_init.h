// Arrays whose entries are left uninitialised until written: for large arrays that a parallel
// pass fills whole, so that their pages are first touched (and zeroed by the kernel) on all
// threads, instead of by a value-initialising fill on the calling thread first.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <utility>

namespace bluetile {

// std::allocator that default-initialises (trivial types: leaves alone) what resize() adds.
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>& other) noexcept : std::allocator<T>(other) {}
  template <class U>
  void construct(U* p) noexcept(noexcept(::new (static_cast<void*>(p)) U)) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// n entries, default-initialised (trivial types: uninitialised).
template <class T>
std::unique_ptr<T[]> default_init_array(std::size_t n) {
  return std::unique_ptr<T[]>(new T[n]);
}

}  // namespace bluetile
