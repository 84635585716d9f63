#pragma once
/// @file
/// What a sweep found: the success rate with its 95 % Wilson interval overall and for every value
/// of every varied parameter (random ranges in equal-width bins), the verdicts counted, and each
/// metric's median and 95th percentile over the trials where it is defined.

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mjarm/sweep/sweep_results.hpp"

namespace mjarm {

/// A success rate and its Wilson score interval.
struct SuccessRate {
  std::int64_t successes = 0;
  std::int64_t trials = 0;
  double rate = 0.0;  ///< successes / trials (0 without trials)
  double low = 0.0;   ///< the interval's ends
  double high = 1.0;
};

/// The Wilson score interval of @p successes in @p trials at @p z standard deviations (1.96:
/// 95 %); [0, 1] without trials.
SuccessRate wilson_interval(std::int64_t successes, std::int64_t trials, double z = 1.959963985);

/// One metric over a group of trials.
struct MetricSummary {
  std::string name;
  std::string unit;
  std::int64_t count = 0;  ///< trials where it is defined
  double median = 0.0;     ///< NaN when count is 0
  double p95 = 0.0;        ///< nearest rank
};

/// One value (or bin) of one varied parameter.
struct ReportGroup {
  std::string parameter;
  nlohmann::ordered_json value;  ///< the value, or [low, high] for a bin of a random range
  SuccessRate success;
  std::vector<MetricSummary> metrics;
};

struct SweepReport {
  std::string scenario;
  std::string hash;
  std::int64_t planned = 0;  ///< the plan's trials (more than the rows while shards are missing)
  SuccessRate success;
  std::map<std::string, std::int64_t> verdicts;
  std::vector<MetricSummary> metrics;
  std::vector<ReportGroup> groups;  ///< per varied parameter, in plan order, values in order
};

/// The report of @p folder's merged results.
/// @throws Error as `read_trials`
SweepReport sweep_report(const SweepFolder& folder);

nlohmann::ordered_json sweep_report_json(const SweepReport& report);

}  // namespace mjarm
