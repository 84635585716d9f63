#include "mjarm/soak/growth_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

void GrowthLimits::check() const { check_fields(*this); }

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

namespace {

// the slope-and-rise rule on one memory figure (see growth_check.hpp)
MemoryGrowth memory_growth(std::span<const SoakSample> samples, int warmup, bool judged,
                           double (*figure)(const ProcessSample&), double max_slope,
                           double margin) {
  MemoryGrowth g;
  g.first = g.min = g.max = figure(samples.front().process);
  g.last = figure(samples.back().process);
  std::vector<double> hours, values;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double v = figure(samples[k].process);
    g.min = std::min(g.min, v);
    g.max = std::max(g.max, v);
    if (static_cast<int>(k) < warmup) {
      g.warmup_max = std::max(g.warmup_max, v);
    } else {
      hours.push_back(samples[k].elapsed_s / 3600.0);
      values.push_back(v);
    }
  }
  if (judged) {
    g.slope = least_squares_slope(hours, values);
    g.growth = g.slope > max_slope && g.last > g.warmup_max + margin;
  }
  return g;
}

}  // namespace

GrowthReport check_growth(std::span<const SoakSample> samples, const GrowthLimits& limits) {
  limits.check();
  GrowthReport r;
  r.samples = static_cast<int>(samples.size());
  if (samples.empty()) return r;
  const int n = r.samples;
  const int share = static_cast<int>(std::ceil(limits.warmup_fraction * n));
  r.warmup_rounds = std::min(std::max(limits.warmup_rounds, share), n);
  r.judged = n - r.warmup_rounds >= kMinJudgedRounds;
  r.heap = memory_growth(
      samples, r.warmup_rounds, r.judged, [](const ProcessSample& p) { return p.heap_kib; },
      limits.max_heap_slope_kib_per_hour, limits.heap_margin_kib);
  r.rss = memory_growth(
      samples, r.warmup_rounds, r.judged, [](const ProcessSample& p) { return p.rss_kib; },
      limits.max_rss_slope_kib_per_hour, limits.rss_margin_kib);
  const ProcessSample& first = samples.front().process;
  const ProcessSample& last = samples.back().process;
  r.fds_first = r.fds_max = first.fds;
  r.threads_first = r.threads_max = first.threads;
  r.fds_last = last.fds;
  r.threads_last = last.threads;
  for (int k = 0; k < n; ++k) {
    const ProcessSample& p = samples[static_cast<std::size_t>(k)].process;
    r.fds_max = std::max(r.fds_max, p.fds);
    r.threads_max = std::max(r.threads_max, p.threads);
    if (k < r.warmup_rounds) {
      r.fds_warmup_max = std::max(r.fds_warmup_max, p.fds);
      r.threads_warmup_max = std::max(r.threads_warmup_max, p.threads);
    } else {
      r.fd_growth = r.fd_growth || p.fds > r.fds_warmup_max;
      r.thread_growth = r.thread_growth || p.threads > r.threads_warmup_max;
    }
  }
  return r;
}

}  // namespace mjarm
