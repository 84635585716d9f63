#pragma once
/// @file
/// `WorkerPool`: a fixed set of threads that run one indexed job at a time, for stepping the
/// environments of a batch in parallel.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mjarm {

/// Runs `job(i)` for i in [0, count) on `threads()` threads (the caller's and threads() − 1
/// workers that live as long as the pool). Indices are handed out one at a time from a shared
/// counter, so which thread runs which index varies; jobs must therefore be independent of each
/// other and of the thread that runs them. `run` allocates nothing and returns when every job
/// has finished; an exception thrown by a job is rethrown there (the first one; the other jobs
/// still run).
class WorkerPool {
 public:
  /// @param threads 1 to 256 (1: everything runs on the caller's thread)
  /// @throws Error for a count out of range.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const noexcept { return static_cast<int>(workers_.size()) + 1; }

  /// The CPU time [s] each thread spent in the last `run` (CLOCK_THREAD_CPUTIME_ID, read at the
  /// start and end of its share: two clock reads per thread and run): entry 0 the caller's,
  /// entry k worker k's. Their sum is the run's work; their maximum the run's critical path on
  /// free cores, whatever else the machine runs (time a thread waits for a core is not counted).
  const std::vector<double>& last_cpu_seconds() const noexcept { return cpu_seconds_; }

  /// Calls @p job(i) for every i in [0, count), in parallel.
  template <class Job>
  void run(int count, Job& job) {
    run_erased(
        count, [](void* context, int i) { (*static_cast<Job*>(context))(i); }, &job);
  }

 private:
  using Function = void (*)(void*, int);
  void run_erased(int count, Function function, void* context);
  void work(int slot) noexcept;
  void worker_loop(int slot) noexcept;

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_;
  std::condition_variable done_;
  std::uint64_t generation_ = 0;
  bool stopping_ = false;
  int busy_ = 0;  // workers still in the current generation
  // the current job
  Function function_ = nullptr;
  void* context_ = nullptr;
  int count_ = 0;
  std::atomic<int> next_{0};
  std::exception_ptr error_;
  std::vector<double> cpu_seconds_;  // per thread, of the last run
};

}  // namespace mjarm
