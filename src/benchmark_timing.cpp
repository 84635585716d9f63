#include "mjarm/benchmark_timing.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace mjarm {

double thread_cpu_seconds() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double steady_seconds() noexcept {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double benchmark_seconds(bool thread_cpu) noexcept {
  return thread_cpu ? thread_cpu_seconds() : steady_seconds();
}

double nearest_rank(const std::vector<double>& sorted, double q) noexcept {
  if (sorted.empty()) return 0.0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace mjarm
