#include "mjarm/sweep/local_backend.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "folder_lock.hpp"
#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"

namespace mjarm {

LocalSweepResult run_sweep_local(const SweepFolder& folder, const SweepPlan& plan,
                                 const LocalSweepOptions& options) {
  if (options.jobs < 0)
    throw Error("sweep: jobs must be ≥ 0 (0: one per core), got " + std::to_string(options.jobs));
  const FolderLock lock(folder.dir, "sweep folder");  // one run or merge at a time
  const auto t0 = std::chrono::steady_clock::now();
  const ShardStates states = shard_states(folder, plan);
  const std::vector<std::int64_t> to_run = states.to_run();

  LocalSweepResult result;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  result.jobs =
      std::max(1, std::min<int>(options.jobs > 0 ? options.jobs : cores,
                                static_cast<int>(std::max<std::size_t>(to_run.size(), 1))));
  std::int64_t done = 0;
  for (const std::int64_t k : states.done) done += plan.shard(k).count;

  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // the counts, the progress callback and the first error
  std::exception_ptr error;
  const auto work = [&] {
    while (true) {
      const std::size_t i = next.fetch_add(1);
      if (i >= to_run.size() || interrupt_requested()) return;
      {
        const std::lock_guard lock(mutex);
        if (error) return;
      }
      try {
        const bool written = run_sweep_shard(folder, plan, to_run[i], [&] {
          const std::lock_guard lock(mutex);
          ++done;
          if (options.progress) options.progress(done, plan.trials);
        });
        const std::lock_guard lock(mutex);
        if (written) {
          ++result.shards_run;
          result.trials_run += plan.shard(to_run[i]).count;
        }
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!error) error = std::current_exception();
        return;
      }
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < result.jobs; ++j) workers.emplace_back(work);
  work();
  for (std::thread& w : workers) w.join();
  if (error) std::rethrow_exception(error);

  result.shards_left = static_cast<std::int64_t>(to_run.size()) - result.shards_run;
  result.interrupted = result.shards_left > 0 && interrupt_requested();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace mjarm
