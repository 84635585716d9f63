#include "mjarm/tasks/pick_place/trials.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"

namespace mjarm {

void PickPlaceStat::add(double value) noexcept {
  if (std::isnan(value)) return;
  if (count == 0) {
    mean = max = value;
  } else {
    mean += (value - mean) / (count + 1);
    max = std::max(max, value);
  }
  ++count;
}

double PickPlaceSummary::success_rate() const noexcept {
  return trials > 0 ? static_cast<double>(successes) / trials : PickPlaceTrace::kNaN;
}

PickPlaceSummary summarize(const std::vector<PickPlaceReport>& reports) {
  PickPlaceSummary s;
  for (const PickPlaceReport& r : reports) {
    if (r.failure == PickPlaceFailure::interrupted) {
      ++s.interrupted;
      continue;
    }
    ++s.trials;
    ++s.failures[static_cast<std::size_t>(r.failure)];
    if (r.trace.welded) {
      s.weld_jump.add(r.trace.weld_jump);
      s.weld_settle.add(r.trace.weld_settle);
    }
    if (r.trace.closed) s.max_slip.add(r.trace.max_slip);
    if (!r.success) continue;
    ++s.successes;
    s.placement_error.add(r.placement_error);
    s.cycle_time.add(r.cycle_time);
    s.grasp_force.add(r.trace.transport_force_mean);
  }
  s.failures[0] = 0;
  return s;
}

PickPlaceBatch run_pick_place_trials(const PickPlaceBatchOptions& options) {
  if (options.trials < 1)
    throw Error("pick and place: trials must be ≥ 1, got " + std::to_string(options.trials));
  if (options.threads < 0)
    throw Error("pick and place: threads must be ≥ 0 (0: one per core), got " +
                std::to_string(options.threads));
  // every trial of the batch draws from the same options: a bad one fails the first trial
  // before it runs, so check it once here, before any worker starts
  (void)draw_pick_place_trial(options.base);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int workers = std::min(options.trials, options.threads > 0 ? options.threads : cores);

  std::vector<std::optional<PickPlaceReport>> slots(static_cast<std::size_t>(options.trials));
  std::atomic<int> next{0};
  std::mutex lock;
  int done = 0;
  std::exception_ptr first_error;
  const auto work = [&] {
    for (;;) {
      if (interrupt_requested()) return;
      {
        const std::lock_guard<std::mutex> guard(lock);
        if (first_error) return;
      }
      const int k = next.fetch_add(1);
      if (k >= options.trials) return;
      PickPlaceOptions trial = options.base;
      trial.seed = options.base.seed + static_cast<std::uint64_t>(k);
      trial.video = {};
      trial.record.clear();
      if (!options.record.empty())
        trial.record = options.record / ("seed_" + std::to_string(trial.seed));
      try {
        PickPlaceReport report = run_pick_place(trial);
        const std::lock_guard<std::mutex> guard(lock);
        slots[static_cast<std::size_t>(k)] = std::move(report);
        ++done;
        if (options.on_progress) options.on_progress(done);
      } catch (...) {
        const std::lock_guard<std::mutex> guard(lock);
        if (!first_error) first_error = std::current_exception();
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(work);
  work();  // the calling thread works too
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);

  PickPlaceBatch batch;
  for (auto& slot : slots) {
    if (!slot) continue;
    if (slot->failure == PickPlaceFailure::interrupted) {
      batch.interrupted = true;
      continue;  // a trial cut short is not a figure
    }
    batch.reports.push_back(std::move(*slot));
  }
  batch.interrupted = batch.interrupted || interrupt_requested();
  batch.summary = summarize(batch.reports);
  return batch;
}

}  // namespace mjarm
