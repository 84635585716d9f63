#pragma once
/// @file
/// The clocks and the percentile the benchmark protocols share (`mjarm bench otg`, `bench traj`,
/// `bench plan`, `bench ik`, `bench control`): a steady wall clock, the calling thread's CPU
/// clock (on a shared machine, time the thread was not running is not counted), and the
/// nearest-rank percentile of the timings.

#include <vector>

namespace mjarm {

/// CPU time consumed by the calling thread so far [s] (CLOCK_THREAD_CPUTIME_ID).
double thread_cpu_seconds() noexcept;

/// Monotonic wall time [s] (std::chrono::steady_clock), from an arbitrary origin.
double steady_seconds() noexcept;

/// thread_cpu_seconds() when @p thread_cpu, else steady_seconds() [s].
double benchmark_seconds(bool thread_cpu) noexcept;

/// The nearest-rank @p q-quantile (q ∈ (0, 1]) of the ascending @p sorted: its ⌈q·n⌉-th value
/// (the first for q·n < 1); 0 when empty.
double nearest_rank(const std::vector<double>& sorted, double q) noexcept;

}  // namespace mjarm
