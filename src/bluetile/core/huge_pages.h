// Transparent huge pages for large arrays read or written at scattered places. A kernel set to
// give them only where asked (/sys/kernel/mm/transparent_hugepage/enabled = madvise, Debian's
// default) backs every other array with 4 KiB pages; a pass that touches one element per page
// at random (the exact engine writes each cell at its site's index, in the order of its own
// spatially sorted vertices) then misses the TLB on nearly every access once the array passes a
// few MiB. Linux: madvise(MADV_HUGEPAGE); elsewhere, and for small arrays, nothing.
#pragma once

#include <cstddef>
#include <vector>

namespace bluetile {

// Asks for huge pages over the whole 2 MiB pages inside [data, data + bytes). Only pages not yet
// touched get them at once (the kernel may merge the others later), so call it on fresh memory.
void advise_huge_pages(void* data, std::size_t bytes);

// Touches [data, data + bytes) once per page on all threads, so that mapping and zeroing fresh
// memory (the kernel's work at a first touch) is shared instead of falling on the thread that
// fills the array first (the exact engine's 560 MB of cells at 10^7 sites: docs/BENCHMARKS.md,
// "The first call's fresh memory").
void touch_pages(void* data, std::size_t bytes);

// Arrays below two huge pages are left alone: the advice could cover at most one page of them.
inline constexpr std::size_t kHugePageArray = std::size_t{4} << 20;

// v = n copies of `value`, in memory advised for huge pages before it is first written when the
// array is large (a new allocation then, even where v's capacity would do).
template <class T>
void assign_on_huge_pages(std::vector<T>& v, std::size_t n, const T& value) {
  if (n * sizeof(T) < kHugePageArray) {
    v.assign(n, value);
    return;
  }
  std::vector<T>().swap(v);
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
  touch_pages(v.data(), n * sizeof(T));
  v.assign(n, value);
}

// v, moved into memory advised for huge pages when large (one copy).
template <class T>
std::vector<T> on_huge_pages(std::vector<T> v) {
  if (v.size() * sizeof(T) < kHugePageArray) return v;
  std::vector<T> copy;
  copy.reserve(v.size());
  advise_huge_pages(copy.data(), v.size() * sizeof(T));
  copy.assign(v.begin(), v.end());
  return copy;
}

}  // namespace bluetile
