#pragma once
/// @file
/// Singularity reports: how close named configurations (keyframes, qpos0, centre, the caller's)
/// and random samples are to losing a direction of motion. Results are structs; nothing prints.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

/// The measures of one configuration.
struct SingularityEntry {
  std::string name;
  Eigen::VectorXd q;               ///< chain order [rad or m]
  SingularValues singular_values;  ///< of the measured block, decreasing
  double sigma_min = 0.0;          ///< smallest singular value
  double condition_number = 0.0;   ///< σmax/σmin, +infinity when singular
  double manipulability = 0.0;     ///< Yoshikawa w
  SingularityStatus status = SingularityStatus::singular;
  bool below_sigma_min = false;         ///< σmin < thresholds.sigma_min (absolute)
  bool above_condition_number = false;  ///< σmax/σmin > thresholds.condition_number (relative)
  /// Empty when neither threshold is crossed; else the kinds found, or {unclassified} (see
  /// `SingularityClassification::kinds`).
  std::vector<SingularityKind> kinds;
  /// Right singular vector of σmin: the joint motion that moves the frame least (unit, chain
  /// order, largest entry positive).
  Eigen::VectorXd null_direction;
  SingularityGeometry geometry;  ///< the measures the kinds are judged on
};

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

/// Result of a random scan.
struct SingularityScan {
  ManipulabilityOptions options;
  SingularityThresholds thresholds;
  SamplingStatus status = SamplingStatus::complete;
  std::size_t samples = 0;  ///< samples drawn (fewer than asked when interrupted)
  std::uint64_t seed = 0;
  std::size_t singular_count = 0;       ///< samples classified singular
  std::size_t near_singular_count = 0;  ///< samples classified near-singular
  /// Samples crossing either threshold (σmin < thresholds.sigma_min or condition above
  /// thresholds.condition_number).
  std::size_t flagged_count = 0;
  /// The lowest-σmin samples, lowest first (at most `keep_worst`), named "sample <index>".
  std::vector<SingularityEntry> worst;
};

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
