#include "bluetile/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>
#include <thread>
#include <vector>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

// Beyond any machine we run on; a larger value is a typo.
constexpr std::size_t kMaxThreads = 1024;

std::size_t default_thread_count() {
  if (const char* env = std::getenv("BLUETILE_THREADS")) {
    std::string_view text(env);
    std::size_t n = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc() || end != text.data() + text.size() || n < 1 || n > kMaxThreads)
      throw Error("BLUETILE_THREADS='" + std::string(text.substr(0, 40)) + "': expected an integer from 1 to " +
                  std::to_string(kMaxThreads));
    return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

std::atomic<std::size_t> configured_threads{0};
thread_local bool inside_parallel_for = false;

// One loop at a time; workers sleep between loops.
class Pool {
 public:
  static Pool& instance() {
    static Pool pool;
    return pool;
  }

  void run(std::size_t workers_wanted, std::size_t chunks,
           const std::function<void(std::size_t)>& chunk_body) {
    std::lock_guard<std::mutex> one_loop(run_mutex_);
    grow(workers_wanted);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      body_ = &chunk_body;
      chunk_count_ = chunks;
      next_chunk_ = 0;
      active_workers_ = std::min(workers_wanted, workers_.size());
      busy_ = active_workers_;
      error_ = nullptr;
      ++generation_;
    }
    wake_.notify_all();
    work();
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    body_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

  ~Pool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      ++generation_;
    }
    wake_.notify_all();
    for (auto& t : workers_) t.join();
  }

 private:
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
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
        if (stopping_) return;
        seen = generation_;
        if (id >= active_workers_) continue;
      }
      work();
      std::lock_guard<std::mutex> lock(mutex_);
      if (--busy_ == 0) done_.notify_all();
    }
  }

  void work() {
    bool was_inside = inside_parallel_for;
    inside_parallel_for = true;
    for (;;) {
      std::size_t chunk = next_chunk_.fetch_add(1);
      if (chunk >= chunk_count_) break;
      try {
        (*body_)(chunk);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
        next_chunk_ = chunk_count_;  // stop handing out work
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
  std::atomic<std::size_t> next_chunk_{0};
  std::size_t active_workers_ = 0;
  std::size_t busy_ = 0;
  std::uint64_t generation_ = 0;
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

void set_thread_count(std::size_t count) { configured_threads = std::max<std::size_t>(1, count); }

void parallel_for(std::size_t count, std::size_t grain,
                  const std::function<void(std::size_t, std::size_t)>& body) {
  if (count == 0) return;
  grain = std::max<std::size_t>(1, grain);
  std::size_t chunks = (count + grain - 1) / grain;
  std::size_t threads = std::min(thread_count(), chunks);
  if (threads <= 1 || inside_parallel_for) {
    body(0, count);
    return;
  }
  std::function<void(std::size_t)> chunk_body = [&](std::size_t chunk) {
    std::size_t begin = chunk * grain;
    body(begin, std::min(count, begin + grain));
  };
  // The calling thread works too, so threads - 1 pool workers are enough.
  Pool::instance().run(threads - 1, chunks, chunk_body);
}

}  // namespace bluetile
