#include "mjarm/tasks/docking/grid.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"

namespace mjarm {

namespace {

void check_axis(const std::vector<double>& values, const char* name) {
  if (values.empty()) throw Error(std::string("docking grid: the ") + name + " axis is empty");
  for (double v : values)
    if (!std::isfinite(v))
      throw Error(std::string("docking grid: a ") + name + " value is not finite");
}

void summarize(DockingGridResult& r) {
  bool first = true;
  for (const DockingGridRun& run : r.runs) {
    const DockingMetrics& m = run.metrics;
    if (run.outcome == DockingOutcome::seated) ++r.seated;
    r.max_peak_force = std::max(r.max_peak_force, m.peak_force);
    r.max_peak_axial_force = std::max(r.max_peak_axial_force, m.peak_axial_force);
    r.max_peak_axial_moment = std::max(r.max_peak_axial_moment, m.peak_axial_moment);
    r.max_lateral = std::max(r.max_lateral, m.max_lateral);
    r.max_tilt = std::max(r.max_tilt, m.max_tilt);
    r.max_position_rms = std::max(r.max_position_rms, m.position_rms);
    r.max_orientation_rms = std::max(r.max_orientation_rms, m.orientation_rms);
    r.min_steady_axial_force =
        first ? m.steady_axial_force : std::min(r.min_steady_axial_force, m.steady_axial_force);
    r.max_steady_axial_force =
        first ? m.steady_axial_force : std::max(r.max_steady_axial_force, m.steady_axial_force);
    first = false;
    for (const std::string& why : m.failures) ++r.failures[why];
  }
}

}  // namespace

DockingGridResult run_docking_grid(const DockingGridOptions& options,
                                   const DockingGridProgress& progress) {
  check_axis(options.x, "x");
  check_axis(options.y, "y");
  check_axis(options.yaw, "yaw");
  if (options.jobs < 0)
    throw Error("docking grid: jobs must be ≥ 0 (0: one per hardware thread), got " +
                std::to_string(options.jobs));
  if (!options.base.record.empty() || !options.base.video.path.empty())
    throw Error("docking grid: a recording or a video belongs to a single run, not to the grid");

  DockingOptions base = options.base;
  base.keep_samples = false;
  base.scene = shared_docking_scene(base.scene, base.joint_friction, base.geometry);
  std::vector<DockingOffset> offsets = options.offsets;
  if (offsets.empty())
    for (double x : options.x)
      for (double y : options.y)
        for (double yaw : options.yaw) offsets.push_back({x, y, yaw});
  for (const DockingOffset& o : offsets) check(o);
  check(base.motion);
  check(base.criteria);
  check(base.controller);
  plan_docking(*base.scene, offsets.front(), base.motion);  // an unreachable start fails here

  DockingGridResult result;
  result.controller = to_string(base.controller.law);
  result.source = base.controller.source;
  result.joint_friction = base.joint_friction;
  result.planned = static_cast<int>(offsets.size());

  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const int jobs =
      std::min(result.planned, options.jobs > 0 ? options.jobs : static_cast<int>(hardware));
  std::vector<std::optional<DockingGridRun>> runs(offsets.size());
  std::atomic<int> next{0};
  std::mutex mutex;
  std::condition_variable changed;
  int done = 0, finished_workers = 0;
  bool stop = false;
  std::exception_ptr error;
  auto worker = [&] {
    for (;;) {
      const int i = next.fetch_add(1);
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (i >= result.planned || stop || interrupt_requested()) break;
      }
      try {
        DockingOptions o = base;
        o.offset = offsets[static_cast<std::size_t>(i)];
        const DockingReport report = run_docking(o);
        std::lock_guard<std::mutex> lock(mutex);
        if (report.outcome == DockingOutcome::interrupted) {
          stop = true;  // cut short: not counted
        } else {
          runs[static_cast<std::size_t>(i)] = DockingGridRun{
              o.offset,        report.outcome,     report.metrics,  report.run.message,
              report.searches, report.search_time, report.seat_time};
          ++done;
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
      changed.notify_all();
    }
    std::lock_guard<std::mutex> lock(mutex);
    ++finished_workers;
    changed.notify_all();
  };
  std::vector<std::thread> threads;
  for (int k = 0; k < jobs; ++k) threads.emplace_back(worker);
  {
    // progress from this thread only (a terminal line is not thread-safe)
    std::unique_lock<std::mutex> lock(mutex);
    int reported = -1;
    while (finished_workers < jobs) {
      if (done != reported && progress) {
        reported = done;
        lock.unlock();
        progress(reported, result.planned);
        lock.lock();
      }
      changed.wait_for(lock, std::chrono::milliseconds(200));
    }
    if (done != reported && progress) progress(done, result.planned);
  }
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  result.interrupted = interrupt_requested() || done < result.planned;
  for (auto& run : runs)
    if (run) result.runs.push_back(std::move(*run));
  summarize(result);
  return result;
}

}  // namespace mjarm
