#pragma once
/// @file
/// Singularity reports: how close named configurations (keyframes, qpos0, centre, the caller's)
/// and random samples are to losing a direction of motion. Results are structs; nothing prints.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/kinematics/singularity_kind.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// A joint configuration with a name (chain order, chain.size() values).
struct NamedConfiguration {
  std::string name;
  Eigen::VectorXd q;
};

/// The measures of one configuration; the fields are documented where they are declared, below.
struct SingularityEntry {
  std::string name;
  Eigen::VectorXd q;
  SingularValues singular_values;
  double sigma_min = 0.0;
  double condition_number = 0.0;
  double manipulability = 0.0;
  SingularityStatus status = SingularityStatus::singular;
  bool below_sigma_min = false;
  bool above_condition_number = false;
  /// Empty when neither threshold is crossed; else the kinds found, or {unclassified} (see
  /// `SingularityClassification::kinds`).
  std::vector<SingularityKind> kinds;
  Eigen::VectorXd null_direction;
  SingularityGeometry geometry;  ///< the measures the kinds are judged on
};

/// The fields of `SingularityEntry` but `kinds` and `geometry` (reported on their own).
constexpr auto declared_fields(const SingularityEntry*) {
  using S = SingularityEntry;
  return declare<S>(
      "singularity entry",
      field("name", &S::name,
            "what the entry is (\"sample <index>\", or the configuration's name)"),
      field("q", &S::q, "rad or m", "configuration, chain order (n,)"),
      field("singular_values", &S::singular_values, "",
            "singular values of the measured block, decreasing (min(m, n),)"),
      field("sigma_min", &S::sigma_min, "", "smallest singular value"),
      field("condition_number", &S::condition_number, "", "σmax/σmin, +inf when singular"),
      field("manipulability", &S::manipulability, "", "Yoshikawa's w = √det(J·Jᵀ)"),
      field("status", &S::status, "regular, near-singular or singular"),
      field("below_sigma_min", &S::below_sigma_min, "σmin < thresholds.sigma_min (absolute)"),
      field("above_condition_number", &S::above_condition_number,
            "σmax/σmin > thresholds.condition_number (relative)"),
      field("null_direction", &S::null_direction, "",
            "right singular vector of σmin: the joint motion that moves the frame least (unit, "
            "chain order, largest entry positive) (n,)"));
}

/// Entries for named configurations, in the order given.
struct SingularityReport {
  ManipulabilityOptions options;
  SingularityThresholds thresholds;
  std::vector<SingularityEntry> entries;
};

/// The standard configurations of a chain: "qpos0" (the model's reference configuration),
/// "center" (middle of the joint ranges, 0 for unlimited joints) and one per keyframe of the
/// model, named after the keyframe ("keyframe <index>" when unnamed). Joints are in chain order.
std::vector<NamedConfiguration> standard_configurations(const Chain& chain);

/// Measures and classifies `standard_configurations(chain)` followed by @p extra.
/// @throws Error when an extra configuration has the wrong size or holds NaN/inf (naming it),
/// or the thresholds in @p options or @p thresholds are invalid.
SingularityReport singularity_report(const Chain& chain,
                                     const std::vector<NamedConfiguration>& extra = {},
                                     const ManipulabilityOptions& options = {},
                                     const SingularityThresholds& thresholds = {});

/// Result of a random scan; the counts are documented where they are declared, below.
struct SingularityScan {
  ManipulabilityOptions options;
  SingularityThresholds thresholds;
  SamplingStatus status = SamplingStatus::complete;
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  std::size_t singular_count = 0;
  std::size_t near_singular_count = 0;
  std::size_t flagged_count = 0;
  std::vector<SingularityEntry> worst;
};

/// The counts and samples of `SingularityScan` (its options, thresholds and status are reported
/// on their own).
constexpr auto declared_fields(const SingularityScan*) {
  using S = SingularityScan;
  return declare<S>(
      "singularity scan",
      field("samples", &S::samples, "", "samples drawn (fewer than asked when interrupted)"),
      field("seed", &S::seed, "", "seed of the samples"),
      field("singular_count", &S::singular_count, "", "samples classified singular"),
      field("near_singular_count", &S::near_singular_count, "", "samples classified near-singular"),
      field("flagged_count", &S::flagged_count, "",
            "samples crossing either threshold (σmin < thresholds.sigma_min or condition above "
            "thresholds.condition_number)"),
      field(
          "worst", &S::worst,
          "the lowest-σmin samples, lowest first (at most keep_worst), named \"sample <index>\""));
}

/// Samples @p samples configurations uniformly within the limits (see `JointSampler`, seeded
/// `Random`: the same seed gives the same scan) and keeps the @p keep_worst samples with
/// the lowest σmin, classified. @p progress, when given, is called with (done, samples) at most
/// ~100 times; @p stop, when given, is asked every thousand samples and ends the scan
/// `SamplingStatus::interrupted` (the counts then cover the samples drawn).
/// @throws Error when @p samples is 0 or the thresholds in @p options or @p thresholds are
/// invalid.
SingularityScan scan_singularities(const Chain& chain, std::size_t samples, std::uint64_t seed,
                                   std::size_t keep_worst = 10,
                                   const ManipulabilityOptions& options = {},
                                   const SingularityThresholds& thresholds = {},
                                   const ProgressCallback& progress = nullptr,
                                   const StopRequest& stop = nullptr);

}  // namespace mjarm
