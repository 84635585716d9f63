#pragma once
/// @file
/// Seeded Monte-Carlo sampling of a chain's reachable workspace: uniform joint samples within the
/// limits, frame positions and manipulability per sample, summary statistics and CSV export.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

/// Draws joint configurations uniformly within a chain's limits; unlimited joints (either bound
/// infinite) are drawn in [−π, π] (rad for hinges, m for slides). Each value uses one 64-bit
/// draw of the generator mapped to [0, 1) by its top 53 bits, so a seed gives the same
/// configurations bit for bit on every platform (no std distribution is involved).
class JointSampler {
 public:
  explicit JointSampler(const Chain& chain);

  /// Writes one configuration (chain.size() values) into @p q. Allocates nothing; @p q must
  /// already have chain.size() entries.
  void sample(Random& rng, Eigen::Ref<Eigen::VectorXd> q) const noexcept;

  /// Lower and upper sampling bounds actually used (finite) [rad or m].
  const Eigen::VectorXd& lower() const noexcept { return lower_; }
  const Eigen::VectorXd& upper() const noexcept { return upper_; }

 private:
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

/// Called with (samples done, samples total) as sampling progresses.
using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;

/// Asked between samples whether to stop early (e.g. `interrupt_requested` after Ctrl-C).
using StopRequest = std::function<bool()>;

/// How a sampling run ended.
enum class SamplingStatus {
  complete,     ///< every requested sample was drawn
  interrupted,  ///< the stop request said so; the statistics cover the samples drawn
};

constexpr auto declared_names(const SamplingStatus*) {
  return std::array{
      EnumName{SamplingStatus::complete, "complete", "every requested sample was drawn"},
      EnumName{SamplingStatus::interrupted, "interrupted", "stopped early on request"}};
}

/// Most samples `sample_workspace` keeps in memory (`keep_points`): 2^25 points, 1 GiB.
inline constexpr std::size_t kMaxKeptWorkspacePoints = std::size_t{1} << 25;

/// Settings of `sample_workspace`.
struct WorkspaceOptions {
  std::size_t samples = 10000;  ///< number of joint samples (> 0)
  std::uint64_t seed = 1;       ///< seed of the `Random` generator
  /// Manipulability block and thresholds; set `compute_manipulability = false` to skip the SVD.
  ManipulabilityOptions manipulability{.block = JacobianBlock::position};
  bool compute_manipulability = true;
  bool keep_points = true;  ///< store every sample in `WorkspaceResult::points`
  /// Optional progress report, called at most ~100 times, always once at the end.
  ProgressCallback progress = nullptr;
  /// Optional stop request, asked about every thousand samples (and once before the first):
  /// when it answers true the run ends `SamplingStatus::interrupted`.
  StopRequest stop = nullptr;
};

constexpr auto declared_fields(const WorkspaceOptions*) {
  using S = WorkspaceOptions;
  return declare<S>(
      "workspace sampling",
      field("samples", &S::samples, "", Range::positive(), "number of joint samples"),
      field("seed", &S::seed, "", Range::non_negative(), "seed of the random generator"),
      field("manipulability", &S::manipulability, "manipulability block and thresholds"),
      field("compute_manipulability", &S::compute_manipulability, "measure manipulability"),
      field("keep_points", &S::keep_points, "store every sample"));
}

/// One sample: where the frame was and how manipulable it was there.
struct WorkspacePoint {
  Eigen::Vector3d p_WE = Eigen::Vector3d::Zero();  ///< frame origin in world [m]
  double manipulability = 0.0;                     ///< w of the chosen block (0 when not computed)
};

/// Summary of a sampling run; the statistics cover all samples even when points are not kept.
struct WorkspaceResult {
  SamplingStatus status = SamplingStatus::complete;
  std::size_t samples = 0;  ///< samples drawn (fewer than asked when interrupted)
  std::uint64_t seed = 0;
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();     ///< bounding-box minimum, world [m]
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();     ///< bounding-box maximum, world [m]
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< mean frame position, world [m]
  /// The chain's base: anchor of its most proximal joint at the centre configuration, world [m].
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();
  double max_reach_from_base = 0.0;    ///< max |p_WE − p_WB| [m]
  double max_reach_from_origin = 0.0;  ///< max |p_WE| [m]
  double min_manipulability = 0.0;     ///< over the samples (0 when not computed)
  double max_manipulability = 0.0;
  double mean_manipulability = 0.0;
  double seconds = 0.0;  ///< wall-clock time of the sampling loop [s] (not deterministic)
  std::vector<WorkspacePoint> points;  ///< every sample, in order, when kept

  /// Writes the points as CSV with header `x,y,z,manipulability`, full double precision, into a
  /// new file renamed over @p path once complete (every write checked, synced before the
  /// rename): @p path holds either its old content or every point, never a truncated list.
  /// @throws Error naming @p path and the system's reason when it cannot be created or written
  ///         (missing folder, full disk).
  void write_csv(const std::filesystem::path& path) const;
};

/// Samples the workspace of @p chain's frame. Uses `ChainKinematics` only (no mjData), so it
/// does not depend on the scene's size; joints outside the chain hold the model's qpos0.
/// The same options and seed give the same points bit for bit.
/// The memory is checked before it is allocated: keeping more than `kMaxKeptWorkspacePoints`
/// points is refused.
/// @throws Error when options.samples is 0, more points than `kMaxKeptWorkspacePoints` would be
///         kept, or the manipulability thresholds are invalid.
WorkspaceResult sample_workspace(const Chain& chain, const WorkspaceOptions& options = {});

}  // namespace mjarm
