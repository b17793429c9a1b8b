// A small persistent thread pool for data-parallel loops. Each thread takes chunks from its own
// segment of the range first and then steals what is left of the others', so which thread runs
// which chunk still varies from run to run: callers must
// make every chunk's result independent of that (each writes only its own outputs), which is
// how the engines stay bit-identical whatever the thread count. A process forked after the pool
// started (Python's multiprocessing) starts workers of its own at its first loop; the fork
// waits for a loop in progress on another thread.
#pragma once

#include <cstddef>
#include <functional>

namespace bluetile {

// Beyond any machine we run on; a larger count is a typo.
inline constexpr std::size_t kMaxThreads = 1024;

// Number of threads used by parallel_for, at least 1. Default: the CPUs this process may run on
// (its affinity mask, as `nproc` counts them), or BLUETILE_THREADS from the environment when set
// and not empty (an integer from 1 to kMaxThreads; anything else throws Error naming it). Both are
// read at the first call that needs them and kept for the process; set_thread_count changes the
// count at any time, and throws Error for a count outside [1, kMaxThreads] (the range the tool's
// --threads and Python's set_thread_count take).
std::size_t thread_count();
void set_thread_count(std::size_t count);

// Calls body(begin, end) over disjoint ranges that cover [0, count), on up to thread_count()
// threads including the caller: chunks of `grain` items (the last one may be shorter) when more
// than one thread takes part; one call body(0, count) on the calling thread when one does (one
// thread, a single chunk, or a nested call), except that one thread runs the chunks in turn while
// a CancelCheck (cancel_check.h) lives on it, so that the check runs between them. Returns when all chunks are done; rethrows the
// first exception a chunk threw, and hands out no more chunks once one has thrown.
void parallel_for(std::size_t count, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace bluetile
