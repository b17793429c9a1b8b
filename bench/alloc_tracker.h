// Heap accounting for the benchmark: this executable replaces the global operator new/delete
// with versions that keep a running total of live bytes (malloc_usable_size of each block) and
// its high-water mark. That measures what C++ code allocates (our engines, CGAL, std
// containers); C code that calls malloc directly (the Vulkan driver) is seen only through
// malloc_held_bytes(). Disabled under AddressSanitizer, which owns the allocator there.
#pragma once

#include <cstddef>

namespace bluetile::bench {

// False when the replacement is compiled out (sanitizer builds): the figures below are then 0.
bool heap_tracking_enabled();
std::size_t heap_live_bytes();
std::size_t heap_peak_bytes();
// Starts a new high-water mark at the current live total.
void heap_reset_peak();

// Bytes glibc's allocator holds for the program, all arenas and mmapped blocks (mallinfo2):
// includes memory that C libraries allocate with malloc.
std::size_t malloc_held_bytes();

}  // namespace bluetile::bench
