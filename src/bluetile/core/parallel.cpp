#include "bluetile/core/parallel.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"

namespace bluetile {
namespace {

// How many CPUs this process may run on, asked once (see thread_count below): its affinity mask,
// as `nproc` counts, which taskset, cpusets and batch schedulers restrict. The machine's count
// instead put two polling threads on one allowed core, 3-5x slower than one thread there.
std::size_t hardware_threads() {
  static const std::size_t count = [] {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) > 0)
      return std::min<std::size_t>(static_cast<std::size_t>(CPU_COUNT(&allowed)), kMaxThreads);
    // A mask wider than cpu_set_t (more than 1024 CPUs) or no answer: the machine's count.
    return std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), kMaxThreads);
  }();
  return count;
}

std::size_t default_thread_count() {
  // Empty counts as unset, as for OMP_NUM_THREADS.
  if (const char* env = std::getenv("BLUETILE_THREADS"); env && *env) {
    std::string_view text(env);
    std::size_t n = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc() || end != text.data() + text.size() || n < 1 || n > kMaxThreads)
      throw Error("BLUETILE_THREADS='" + std::string(text.substr(0, 40)) + "': expected an integer from 1 to " +
                  std::to_string(kMaxThreads));
    return n;
  }
  return hardware_threads();
}

std::atomic<std::size_t> configured_threads{0};
thread_local bool inside_parallel_for = false;
thread_local const std::function<void()>* cancel_check = nullptr;  // the innermost CancelCheck's

// How long a thread that ran out of work polls before it sleeps on a condition variable: a
// woken thread starts 50-60 us late on the 2-core VM of docs/BENCHMARKS.md ("Two threads at
// 10^4 sites"), and a Lloyd iteration's serial part between two loops is about 0.3 ms at 10^4
// sites, so polling this long keeps the next loop's start and this loop's end off the wake-up.
constexpr std::chrono::microseconds kPollTime{500};

void pause_briefly() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

// Polls `ready` until it returns true or kPollTime has passed; returns its last answer.
template <typename Ready>
bool poll(Ready ready) {
  const auto deadline = std::chrono::steady_clock::now() + kPollTime;
  for (;;) {
    for (int k = 0; k < 64; ++k) {
      if (ready()) return true;
      pause_briefly();
    }
    if (std::chrono::steady_clock::now() >= deadline) return ready();
  }
}

// One loop at a time. Threads that run out of work poll for a while (kPollTime), then sleep.
class Pool {
 public:
  static Pool& instance() {
    static Pool pool;
    return pool;
  }

  // A process forked after the pool started its workers (Python's multiprocessing forks by
  // default on Linux) has the pool but not their threads: its first loop waited forever for them.
  // The fork waits for the loop in progress, if any; the child then starts with no workers.
  Pool() {
    pthread_atfork([] { instance().lock_for_fork(); }, [] { instance().unlock_after_fork(); },
                   [] { instance().forget_workers_after_fork(); });
  }

  void run(std::size_t workers_wanted, std::size_t chunks,
           const std::function<void(std::size_t)>& chunk_body) {
    std::lock_guard<std::mutex> one_loop(run_mutex_);
    grow(workers_wanted);
    polling_.store(workers_.size() + 1 <= hardware_threads(), std::memory_order_relaxed);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      body_ = &chunk_body;
      chunk_count_ = chunks;
      active_workers_ = std::min(workers_wanted, workers_.size());
      participants_ = active_workers_ + 1;
      for (std::size_t p = 0; p < participants_; ++p)
        segments_[p].next.store(segment_begin(p), std::memory_order_relaxed);
      busy_ = active_workers_;
      error_ = nullptr;
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    work(0);
    if (!polling() || !poll([&] { return busy_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, [&] { return busy_.load(std::memory_order_acquire) == 0; });
    }
    body_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      generation_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
    for (auto& t : workers_) t.join();
  }

 private:
  void lock_for_fork() {
    run_mutex_.lock();
    mutex_.lock();
  }

  void unlock_after_fork() {
    mutex_.unlock();
    run_mutex_.unlock();
  }

  // In the child, whose only thread is the one that forked: new locks and condition variables
  // (the old ones may count waiters that are not there), and the old workers' std::thread handles
  // dropped without joining or destroying them (either would wait or terminate); the next loop
  // starts workers of its own.
  void forget_workers_after_fork() {
    ::new (&run_mutex_) std::mutex;
    ::new (&mutex_) std::mutex;
    ::new (&wake_) std::condition_variable;
    ::new (&done_) std::condition_variable;
    ::new (&workers_) std::vector<std::thread>;  // the old buffer is left allocated, on purpose
    active_workers_ = 0;
    participants_ = 1;
    busy_.store(0);
  }

  // Polling only while every thread of the pool has a core of its own: with more threads than
  // cores (BLUETILE_THREADS=7 on 2 cores) a polling thread would take the core of one that works.
  bool polling() const { return polling_.load(std::memory_order_relaxed); }

  void grow(std::size_t count) {
    while (workers_.size() < count) {
      std::size_t id = workers_.size();
      try {
        workers_.emplace_back([this, id] { worker_loop(id); });
      } catch (const std::system_error& e) {
        // EAGAIN or ENOMEM: a thread's stack did not fit the memory or thread limit.
        throw Error("cannot start worker thread " + std::to_string(id + 1) + " of " + std::to_string(count) + " (" +
                    e.code().message() + "): out of memory or threads (ulimit -v, ulimit -u); BLUETILE_THREADS=" +
                    std::to_string(id + 1) + " asks for fewer");
      }
    }
  }

  void worker_loop(std::size_t id) {
    inside_parallel_for = true;
    std::uint64_t seen = 0;
    for (;;) {
      auto next_loop = [&] { return generation_.load(std::memory_order_acquire) != seen; };
      if (polling()) poll(next_loop);
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || next_loop(); });
        if (stopping_) return;
        seen = generation_.load(std::memory_order_relaxed);
        if (id >= active_workers_) continue;
      }
      work(id + 1);
      if (busy_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        // Under the lock: the caller, if it sleeps, checked busy_ under it before sleeping.
        std::lock_guard<std::mutex> lock(mutex_);
        done_.notify_all();
      }
    }
  }

  // The chunks of participant p's own segment (the caller is participant 0, pool worker id is id + 1).
  std::size_t segment_begin(std::size_t p) const { return chunk_count_ * p / participants_; }
  std::size_t segment_end(std::size_t p) const { return chunk_count_ * (p + 1) / participants_; }

  // A participant runs its own segment first, then takes what is left of the others'. So the
  // same thread takes the same chunks from one loop to the next unless the load shifts, and a
  // loop over the same data (a Lloyd iteration's cells) keeps each part on one core's cache.
  void work(std::size_t participant) {
    bool was_inside = inside_parallel_for;
    inside_parallel_for = true;
    for (std::size_t k = 0; k < participants_; ++k) {
      const std::size_t p = (participant + k) % participants_;
      const std::size_t end = segment_end(p);
      for (;;) {
        std::size_t chunk = segments_[p].next.fetch_add(1);
        if (chunk >= end) break;
        try {
          (*body_)(chunk);
        } catch (...) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (!error_) error_ = std::current_exception();
          for (std::size_t q = 0; q < participants_; ++q) segments_[q].next = chunk_count_;  // stop handing out work
        }
      }
    }
    inside_parallel_for = was_inside;
  }

  std::mutex run_mutex_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::vector<std::thread> workers_;
  const std::function<void(std::size_t)>* body_ = nullptr;
  std::size_t chunk_count_ = 0;
  // Each polled word on a cache line of its own, apart from the counters the chunks are taken from.
  struct alignas(64) Segment {
    std::atomic<std::size_t> next{0};
  };
  std::size_t participants_ = 1;
  std::unique_ptr<Segment[]> segments_ = std::make_unique<Segment[]>(kMaxThreads + 1);
  alignas(64) std::atomic<std::size_t> busy_{0};
  alignas(64) std::atomic<std::uint64_t> generation_{0};
  std::atomic<bool> polling_{false};
  std::size_t active_workers_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace

std::size_t thread_count() {
  std::size_t n = configured_threads.load();
  if (n) return n;
  // Asked once: glibc reads the online-CPU list from /proc on every hardware_concurrency() call,
  // which cost 3x on runs with many short loops. An invalid BLUETILE_THREADS throws every time.
  static const std::size_t machine_default = default_thread_count();
  return machine_default;
}

void set_thread_count(std::size_t count) {
  if (count < 1 || count > kMaxThreads)
    throw Error("thread count " + std::to_string(count) + ": expected an integer from 1 to " + std::to_string(kMaxThreads));
  configured_threads = count;
}

CancelCheck::CancelCheck(std::function<void()> check) : check_(std::move(check)), previous_(cancel_check) {
  cancel_check = &check_;
}

CancelCheck::~CancelCheck() { cancel_check = previous_; }

void cancellation_point() {
  if (cancel_check != nullptr) (*cancel_check)();
}

void parallel_for(std::size_t count, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body) {
  if (count == 0) return;
  grain = std::max<std::size_t>(1, grain);
  std::size_t chunks = (count + grain - 1) / grain;
  std::size_t threads = std::min(thread_count(), chunks);
  // The caller's check, between the chunks the caller runs (a worker thread has none of its own):
  // what it throws stops the loop as a chunk's error does.
  const std::function<void()>* check = cancel_check;
  if (inside_parallel_for) {
    body(0, count);
    return;
  }
  if (threads <= 1) {
    // One thread: one call, unless a check waits; then the chunks of a parallel run, in turn
    // (a body gives the same bits for any chunks, as the thread count may not change them).
    if (check == nullptr) {
      body(0, count);
      return;
    }
    for (std::size_t begin = 0; begin < count; begin += grain) {
      (*check)();
      body(begin, std::min(count, begin + grain));
    }
    return;
  }
  const std::thread::id caller = std::this_thread::get_id();
  std::function<void(std::size_t)> chunk_body = [&](std::size_t chunk) {
    if (check != nullptr && std::this_thread::get_id() == caller) (*check)();
    std::size_t begin = chunk * grain;
    body(begin, std::min(count, begin + grain));
  };
  // The calling thread works too, so threads - 1 pool workers are enough.
  Pool::instance().run(threads - 1, chunks, chunk_body);
}

}  // namespace bluetile
