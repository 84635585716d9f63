#include "mjarm/soak/growth_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

void GrowthLimits::check() const {
  if (warmup_rounds < 1)
    throw Error("soak warm-up: " + std::to_string(warmup_rounds) + " rounds; expected ≥ 1");
  if (!(warmup_fraction >= 0.0 && warmup_fraction < 1.0))
    throw Error("soak warm-up share: expected a number in [0, 1)");
  if (!(max_rss_slope_kib_per_hour >= 0.0) || !std::isfinite(max_rss_slope_kib_per_hour))
    throw Error("soak RSS slope bound: expected a finite number ≥ 0 KiB/h");
  if (!(rss_margin_kib >= 0.0) || !std::isfinite(rss_margin_kib))
    throw Error("soak RSS margin: expected a finite number ≥ 0 KiB");
}

double least_squares_slope(std::span<const double> x, std::span<const double> y) noexcept {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0.0;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

GrowthReport check_growth(std::span<const SoakSample> samples, const GrowthLimits& limits) {
  limits.check();
  GrowthReport r;
  r.samples = static_cast<int>(samples.size());
  if (samples.empty()) return r;
  const int n = r.samples;
  const int share = static_cast<int>(std::ceil(limits.warmup_fraction * n));
  r.warmup_rounds = std::min(std::max(limits.warmup_rounds, share), n);
  const ProcessSample& first = samples.front().process;
  const ProcessSample& last = samples.back().process;
  r.rss_first = r.rss_min = r.rss_max = first.rss_kib;
  r.fds_first = r.fds_max = first.fds;
  r.threads_first = r.threads_max = first.threads;
  r.rss_last = last.rss_kib;
  r.fds_last = last.fds;
  r.threads_last = last.threads;
  for (int k = 0; k < n; ++k) {
    const ProcessSample& p = samples[static_cast<std::size_t>(k)].process;
    r.rss_min = std::min(r.rss_min, p.rss_kib);
    r.rss_max = std::max(r.rss_max, p.rss_kib);
    r.fds_max = std::max(r.fds_max, p.fds);
    r.threads_max = std::max(r.threads_max, p.threads);
    if (k < r.warmup_rounds) {
      r.rss_warmup_max = std::max(r.rss_warmup_max, p.rss_kib);
      r.fds_warmup_max = std::max(r.fds_warmup_max, p.fds);
      r.threads_warmup_max = std::max(r.threads_warmup_max, p.threads);
    } else {
      r.fd_growth = r.fd_growth || p.fds > r.fds_warmup_max;
      r.thread_growth = r.thread_growth || p.threads > r.threads_warmup_max;
    }
  }
  const int after = n - r.warmup_rounds;
  r.rss_judged = after >= kMinJudgedRounds;
  if (r.rss_judged) {
    std::vector<double> hours, rss;
    for (int k = r.warmup_rounds; k < n; ++k) {
      hours.push_back(samples[static_cast<std::size_t>(k)].elapsed_s / 3600.0);
      rss.push_back(samples[static_cast<std::size_t>(k)].process.rss_kib);
    }
    r.rss_slope = least_squares_slope(hours, rss);
    r.rss_growth = r.rss_slope > limits.max_rss_slope_kib_per_hour &&
                   r.rss_last > r.rss_warmup_max + limits.rss_margin_kib;
  }
  return r;
}

}  // namespace mjarm
