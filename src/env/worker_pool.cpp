#include "mjarm/env/worker_pool.hpp"

#include <string>

#include "mjarm/benchmark_timing.hpp"
#include "mjarm/error.hpp"

namespace mjarm {

WorkerPool::WorkerPool(int threads) {
  if (threads < 1 || threads > 256)
    throw Error("worker pool: threads must be from 1 to 256, got " + std::to_string(threads));
  cpu_seconds_.assign(static_cast<std::size_t>(threads), 0.0);
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { worker_loop(t); });
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void WorkerPool::work(int slot) noexcept {
  const double start = thread_cpu_seconds();
  for (int i = next_.fetch_add(1, std::memory_order_relaxed); i < count_;
       i = next_.fetch_add(1, std::memory_order_relaxed)) {
    try {
      function_(context_, i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!error_) error_ = std::current_exception();
    }
  }
  cpu_seconds_[static_cast<std::size_t>(slot)] = thread_cpu_seconds() - start;  // this slot's own
}

void WorkerPool::worker_loop(int slot) noexcept {
  std::uint64_t seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
    }
    work(slot);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      --busy_;
    }
    done_.notify_one();
  }
}

void WorkerPool::run_erased(int count, Function function, void* context) {
  if (count <= 0) return;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    function_ = function;
    context_ = context;
    count_ = count;
    next_.store(0, std::memory_order_relaxed);
    error_ = nullptr;
    busy_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  if (!workers_.empty()) start_.notify_all();
  work(0);
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    error = error_;
    error_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace mjarm
