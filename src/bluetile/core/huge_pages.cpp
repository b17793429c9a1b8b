#include "bluetile/core/huge_pages.h"

#include <cstdint>

#include "bluetile/core/parallel.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace bluetile {

void advise_huge_pages(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
  // A hint: a kernel without transparent huge pages refuses it, and the pages stay small.
  if (first < last) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

void touch_pages(void* data, std::size_t bytes) {
  // One byte per small page: a huge page is mapped (and zeroed) whole by its first touch.
  constexpr std::size_t kPage = 4096, kGrain = 512;  // 2 MiB of pages per chunk
  auto* bytes_at = static_cast<volatile unsigned char*>(data);
  const std::size_t pages = (bytes + kPage - 1) / kPage;
  parallel_for(pages, kGrain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t p = begin; p < end; ++p) bytes_at[p * kPage] = 0;
  });
}

}  // namespace bluetile
