// The thread pool (parallel.h): every item visited exactly once in chunks of the grain asked,
// whatever the thread count and however the chunks fall on the threads (each thread's own
// segment first, then stealing), the first exception rethrown and the rest of the work stopped,
// nested loops run on the calling thread; a CancelCheck runs on the calling thread between its
// chunks, and what it throws ends the loop.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// Restores the thread count a test changed.
class ThreadCountGuard {
 public:
  ThreadCountGuard() : saved_(thread_count()) {}
  ~ThreadCountGuard() { set_thread_count(saved_); }

 private:
  std::size_t saved_;
};

TEST(Parallel, EveryItemOnceInChunksOfTheGrainForAnyThreadCount) {
  ThreadCountGuard guard;
  // Counts below, at and above the participants, grains that do and do not divide the count.
  for (std::size_t threads : {1u, 2u, 3u, 7u}) {
    set_thread_count(threads);
    for (std::size_t count : {1u, 2u, 5u, 7u, 8u, 64u, 1000u, 4097u}) {
      for (std::size_t grain : {1u, 3u, 16u, 5000u}) {
        std::vector<std::atomic<int>> visits(count);
        std::atomic<std::size_t> bad_chunks{0};
        const bool serial = threads == 1 || count <= grain;
        parallel_for(count, grain, [&](std::size_t begin, std::size_t end) {
          if (serial) {
            // One call over the whole range.
            if (begin != 0 || end != count) ++bad_chunks;
          } else if (begin % grain != 0 || end <= begin || end - begin > grain || (end - begin < grain && end != count)) {
            // A chunk starts on a multiple of the grain and is a whole grain unless it is the last.
            ++bad_chunks;
          }
          for (std::size_t i = begin; i < end; ++i) ++visits[i];
        });
        EXPECT_EQ(bad_chunks.load(), 0u) << threads << " threads, count " << count << ", grain " << grain;
        std::size_t wrong = 0;
        for (auto& v : visits) wrong += v.load() != 1;
        EXPECT_EQ(wrong, 0u) << threads << " threads, count " << count << ", grain " << grain;
      }
    }
  }
}

TEST(Parallel, ThreadCountsOutsideOneToTheLimitAreRefusedNotClamped) {
  // 0 was taken as 1 and any count above the limit started that many threads; the front ends
  // refuse both (--threads, set_thread_count in Python) with this range.
  ThreadCountGuard guard;
  set_thread_count(3);
  for (std::size_t bad : {std::size_t{0}, kMaxThreads + 1, std::size_t{1} << 40}) {
    try {
      set_thread_count(bad);
      ADD_FAILURE() << bad << " threads accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "thread count " + std::to_string(bad) + ": expected an integer from 1 to 1024");
    }
    EXPECT_EQ(thread_count(), 3u) << "a refused count changed the count";
  }
  set_thread_count(kMaxThreads);
  EXPECT_EQ(thread_count(), kMaxThreads);
  set_thread_count(1);
  EXPECT_EQ(thread_count(), 1u);
}

TEST(Parallel, ManyLoopsInARowLoseNoChunk) {
  // The segments are reset per loop: a worker that wakes late for one loop must neither miss the
  // next nor run a chunk of the previous one again.
  ThreadCountGuard guard;
  set_thread_count(2);
  std::vector<std::atomic<int>> visits(37);
  for (int loop = 0; loop < 2000; ++loop)
    parallel_for(visits.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) ++visits[i];
    });
  for (auto& v : visits) EXPECT_EQ(v.load(), 2000);
}

TEST(Parallel, UsesMoreThanOneThreadWhenAsked) {
  ThreadCountGuard guard;
  set_thread_count(2);
  // Each chunk waits until two distinct threads have started one (bounded, so a pool that ran
  // everything on the caller fails instead of hanging).
  std::atomic<int> started{0};
  std::set<std::thread::id> ids;
  std::mutex ids_mutex;
  parallel_for(2, 1, [&](std::size_t, std::size_t) {
    {
      std::lock_guard<std::mutex> lock(ids_mutex);
      ids.insert(std::this_thread::get_id());
    }
    ++started;
    for (int k = 0; k < 2000 && started.load() < 2; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  EXPECT_EQ(ids.size(), 2u);
}

TEST(Parallel, AProcessForkedAfterTheWorkersStartedRunsLoopsOnThreadsOfItsOwn) {
  // Python's multiprocessing forks by default on Linux: the child has the pool but not its
  // workers, and its first loop waited for them forever.
  ThreadCountGuard guard;
  for (std::size_t threads : {2u, 7u}) {
    set_thread_count(threads);
    parallel_for(64, 1, [](std::size_t, std::size_t) {});  // the workers are running
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      alarm(60);  // a hang ends the child by SIGALRM, which the parent reports
      std::vector<std::atomic<int>> visits(1000);
      std::set<std::thread::id> ids;
      std::mutex ids_mutex;
      std::atomic<int> started{0};
      for (int loop = 0; loop < 100; ++loop)
        parallel_for(visits.size(), 7, [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) ++visits[i];
        });
      // And more than one thread takes part, as in UsesMoreThanOneThreadWhenAsked.
      parallel_for(2, 1, [&](std::size_t, std::size_t) {
        {
          std::lock_guard<std::mutex> lock(ids_mutex);
          ids.insert(std::this_thread::get_id());
        }
        ++started;
        for (int k = 0; k < 2000 && started.load() < 2; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      });
      bool every_item_100_times = true;
      for (auto& v : visits) every_item_100_times = every_item_100_times && v.load() == 100;
      _exit(every_item_100_times && ids.size() == 2 ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status)) << threads << " threads: the child ended by signal "
                                   << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << " (14: SIGALRM, it hung)";
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << threads << " threads: items missed or one thread ran";
    // The parent's pool goes on as before.
    std::atomic<std::size_t> sum{0};
    parallel_for(100, 3, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) sum += i;
    });
    EXPECT_EQ(sum.load(), 4950u);
  }
}

TEST(Parallel, FirstExceptionIsRethrownAndTheRestOfTheWorkStops) {
  ThreadCountGuard guard;
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    // Chunk 0 is the caller's first; every other chunk takes at least 50 us, so running them
    // all would take 100 ms on one thread and stopping leaves most of them undone, even if a
    // busy machine holds the caller back for a few milliseconds before it throws.
    std::atomic<std::size_t> chunks_run{0};
    EXPECT_THROW(parallel_for(2000, 1,
                              [&](std::size_t begin, std::size_t) {
                                ++chunks_run;
                                if (begin == 0) throw std::runtime_error("chunk 0 failed");
                                std::this_thread::sleep_for(std::chrono::microseconds(50));
                              }),
                 std::runtime_error)
        << threads << " threads";
    if (threads == 1) {
      EXPECT_EQ(chunks_run.load(), 1u);  // the one call over the whole range
    }
    EXPECT_LT(chunks_run.load(), 1000u) << threads << " threads";
    // The pool is usable after a failed loop.
    std::atomic<std::size_t> sum{0};
    parallel_for(1000, 7, [&](std::size_t begin, std::size_t end) { sum += end - begin; });
    EXPECT_EQ(sum.load(), 1000u);
  }
}

TEST(Parallel, NestedLoopsRunOnTheCallingThread) {
  ThreadCountGuard guard;
  set_thread_count(2);
  std::atomic<std::size_t> nested_off_thread{0}, nested_items{0};
  parallel_for(8, 1, [&](std::size_t, std::size_t) {
    const auto outer = std::this_thread::get_id();
    parallel_for(50, 1, [&](std::size_t begin, std::size_t end) {
      if (std::this_thread::get_id() != outer) ++nested_off_thread;
      nested_items += end - begin;
    });
  });
  EXPECT_EQ(nested_off_thread.load(), 0u);
  EXPECT_EQ(nested_items.load(), 8u * 50u);
}

TEST(Parallel, ACancelCheckRunsOnTheCallingThreadAndWhatItThrowsEndsTheLoop) {
  ThreadCountGuard guard;
  set_thread_count(2);
  const auto caller = std::this_thread::get_id();
  std::atomic<std::size_t> checks{0}, off_thread{0};
  {
    CancelCheck check([&] {
      ++checks;
      if (std::this_thread::get_id() != caller) ++off_thread;
    });
    std::atomic<std::size_t> items{0};
    parallel_for(400, 1, [&](std::size_t begin, std::size_t end) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
      items += end - begin;
    });
    EXPECT_EQ(items.load(), 400u);  // checking changes nothing else
    EXPECT_GT(checks.load(), 0u);
    EXPECT_EQ(off_thread.load(), 0u);
    const std::size_t before = checks.load();
    cancellation_point();
    EXPECT_EQ(checks.load(), before + 1);
  }
  // Gone with its object: neither the loops nor cancellation_point() call it.
  const std::size_t after = checks.load();
  parallel_for(400, 1, [](std::size_t, std::size_t) {});
  cancellation_point();
  EXPECT_EQ(checks.load(), after);

  // A check that throws ends the loop with its exception, most chunks not run (each takes 50 us:
  // all would take 100 ms), and the pool works after it.
  std::atomic<std::size_t> chunks_run{0};
  {
    std::size_t calls = 0;
    CancelCheck check([&] {
      if (++calls == 3) throw std::runtime_error("cancelled");
    });
    EXPECT_THROW(parallel_for(2000, 1,
                              [&](std::size_t, std::size_t) {
                                ++chunks_run;
                                std::this_thread::sleep_for(std::chrono::microseconds(50));
                              }),
                 std::runtime_error);
  }
  EXPECT_LT(chunks_run.load(), 1000u);
  std::atomic<std::size_t> sum{0};
  parallel_for(1000, 7, [&](std::size_t begin, std::size_t end) { sum += end - begin; });
  EXPECT_EQ(sum.load(), 1000u);

  // Nested: the inner check replaces the outer one while it lives.
  std::size_t outer_calls = 0, inner_calls = 0;
  CancelCheck outer([&] { ++outer_calls; });
  {
    CancelCheck inner([&] { ++inner_calls; });
    cancellation_point();
  }
  cancellation_point();
  EXPECT_EQ(inner_calls, 1u);
  EXPECT_EQ(outer_calls, 1u);
}

TEST(Parallel, OnOneThreadACancelCheckRunsBetweenTheChunksWhichMatchAParallelRun) {
  // One thread ran the loop as one call and never reached the check: Python's Ctrl-C waited for
  // the whole loop under BLUETILE_THREADS=1.
  ThreadCountGuard guard;
  set_thread_count(1);
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  std::size_t checks = 0;
  {
    CancelCheck check([&] { ++checks; });
    parallel_for(10, 4, [&](std::size_t begin, std::size_t end) { ranges.emplace_back(begin, end); });
  }
  const std::vector<std::pair<std::size_t, std::size_t>> chunks{{0, 4}, {4, 8}, {8, 10}};
  EXPECT_EQ(ranges, chunks);
  EXPECT_EQ(checks, 3u);
  // Without a check, one call, as before.
  ranges.clear();
  parallel_for(10, 4, [&](std::size_t begin, std::size_t end) { ranges.emplace_back(begin, end); });
  EXPECT_EQ(ranges, (std::vector<std::pair<std::size_t, std::size_t>>{{0, 10}}));
  // A check that throws stops the loop before the next chunk.
  std::size_t run = 0, calls = 0;
  CancelCheck check([&] {
    if (++calls == 2) throw std::runtime_error("cancelled");
  });
  EXPECT_THROW(parallel_for(100, 1, [&](std::size_t, std::size_t) { ++run; }), std::runtime_error);
  EXPECT_EQ(run, 1u);
}

}  // namespace
}  // namespace bluetile
