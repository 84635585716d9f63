#pragma once
/// @file
/// Growth of a process over the rounds of a soak: resident memory (a leak), open file descriptors
/// and threads, judged after a warm-up.
///
/// The rule. The first max(`warmup_rounds`, ⌈`warmup_fraction` · samples⌉) samples are the
/// warm-up: caches, allocator arenas and lazily built tables settle there. Over the samples after
/// it:
/// - the heap in use (what a leak grows) grows when BOTH its least-squares slope against elapsed
///   time exceeds `max_heap_slope_kib_per_hour` AND the last sample exceeds the warm-up's
///   largest by more than `heap_margin_kib` (a rise alone can be a cache filled once after the
///   warm-up, or the last round's transient; a slope alone, noise within the margin); it needs
///   at least
///   `kMinJudgedRounds` samples after the warm-up, else it is not judged;
/// - resident memory, by the same rule with its own, coarser bounds: the allocator keeps freed
///   memory in its per-thread arenas, and that retention rises for minutes towards a plateau (the
///   hour-long run, docs/hardening.md) without a byte leaked; the RSS rule catches what the heap
///   does not see (mmap outside malloc, thread stacks) when it is large;
/// - file descriptors grow when any sample after the warm-up holds more than the warm-up's
///   largest count; threads alike.

#include <span>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/soak/process_sample.hpp"

namespace mjarm {

/// One round's sample.
struct SoakSample {
  int round = 0;           ///< 1-based
  double elapsed_s = 0.0;  ///< since the soak started, at the end of the round [s]
  ProcessSample process;
};

/// Bounds of the growth rule (see the file's comment).
struct GrowthLimits {
  int warmup_rounds = 5;                        ///< at least this many rounds (≥ 1)
  double warmup_fraction = 0.1;                 ///< and at least this share of them [0, 1)
  double max_heap_slope_kib_per_hour = 256.0;   ///< ≥ 0 [KiB/h]
  double heap_margin_kib = 256.0;               ///< ≥ 0 [KiB]
  double max_rss_slope_kib_per_hour = 16384.0;  ///< ≥ 0 [KiB/h]
  double rss_margin_kib = 32768.0;              ///< ≥ 0 [KiB]
  /// @throws Error naming the first bound out of range.
  void check() const;
};

constexpr auto declared_fields(const GrowthLimits*) {
  using S = GrowthLimits;
  return declare<S>(
      "soak",
      field("warmup_rounds", &S::warmup_rounds, "", Range::at_least(1),
            "at least this many warm-up rounds"),
      field("warmup_fraction", &S::warmup_fraction, "", Range{0.0, 1.0, false, true, false},
            "and at least this share of the rounds"),
      field("max_heap_slope_kib_per_hour", &S::max_heap_slope_kib_per_hour, "KiB/h",
            Range::non_negative(), "heap growth allowed after the warm-up"),
      field("heap_margin_kib", &S::heap_margin_kib, "KiB", Range::non_negative(),
            "heap above the warm-up's largest allowed"),
      field("max_rss_slope_kib_per_hour", &S::max_rss_slope_kib_per_hour, "KiB/h",
            Range::non_negative(), "RSS growth allowed after the warm-up"),
      field("rss_margin_kib", &S::rss_margin_kib, "KiB", Range::non_negative(),
            "RSS above the warm-up's largest allowed"));
}

/// Samples after the warm-up needed to judge memory growth.
inline constexpr int kMinJudgedRounds = 3;

/// What the rule found for one memory figure, in KiB (slope in KiB per hour).
struct MemoryGrowth {
  double first = 0.0, min = 0.0, max = 0.0, last = 0.0;
  double warmup_max = 0.0;  ///< largest of the warm-up
  double slope = 0.0;       ///< least-squares slope after the warm-up (0 when not judged)
  bool growth = false;
};

/// What the rule found.
struct GrowthReport {
  int samples = 0;
  int warmup_rounds = 0;  ///< the warm-up actually used (fewer samples: all of them)
  bool judged = false;    ///< at least kMinJudgedRounds samples after the warm-up (memory)
  MemoryGrowth heap;      ///< heap in use
  MemoryGrowth rss;       ///< resident memory
  int fds_first = 0, fds_warmup_max = 0, fds_max = 0, fds_last = 0;
  bool fd_growth = false;
  int threads_first = 0, threads_warmup_max = 0, threads_max = 0, threads_last = 0;
  bool thread_growth = false;
  bool grew() const noexcept {
    return heap.growth || rss.growth || fd_growth || thread_growth;
  }
};

/// Least-squares slope of @p y against @p x (0 for fewer than two points or a constant x).
double least_squares_slope(std::span<const double> x, std::span<const double> y) noexcept;

/// Applies the rule to @p samples (in round order) with @p limits (checked).
/// @throws Error for limits out of range.
GrowthReport check_growth(std::span<const SoakSample> samples, const GrowthLimits& limits);

}  // namespace mjarm
