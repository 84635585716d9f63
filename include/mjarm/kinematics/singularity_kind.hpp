#pragma once
/// @file
/// The kind of a singularity (wrist, elbow, shoulder), found from the geometry of the chain's
/// joint axes, with the absolute and relative thresholds the classic tools use to call a
/// configuration singular, and the joint direction that is lost.

#include <Eigen/Core>
#include <limits>
#include <utility>
#include <vector>

#include "mjarm/kinematics/manipulability.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Why an arm loses a direction of motion.
enum class SingularityKind {
  wrist,     ///< two wrist axes aligned (parallel; collinear for a spherical wrist)
  elbow,     ///< arm stretched or folded: no elbow joint can change the shoulder–wrist distance
  shoulder,  ///< the wrist centre on the first joint axis
  unclassified  ///< singular, but none of the above applies or can be judged on this chain
};

constexpr auto declared_names(const SingularityKind*) {
  using K = SingularityKind;
  return std::array{EnumName{K::wrist, "wrist", "two wrist axes aligned"},
                    EnumName{K::elbow, "elbow", "arm stretched or folded"},
                    EnumName{K::shoulder, "shoulder", "the wrist centre on the first joint axis"},
                    EnumName{K::unclassified, "unclassified", "singular, no kind applies"}};
}

/// The parts of an arm, found from its joint axes at two configurations (chain indices).
/// Judged only on chains of at least 6 hinge joints that all move the frame.
struct ArmStructure {
  /// At least 6 hinges, all on the frame's path: the kinds can be judged.
  bool classifiable = false;
  /// The first 2 or 3 joints when their axes meet at one point (the shoulder centre S), and
  /// at least one joint lies between them and the wrist; empty otherwise.
  std::vector<int> shoulder;
  /// The joints between the shoulder and the wrist (the elbow); empty without a shoulder.
  std::vector<int> middle;
  /// The last three joints.
  std::vector<int> wrist;
  /// True when the last three axes meet at one point (the wrist centre W).
  bool spherical_wrist = false;
  /// True, without a spherical wrist, when the first wrist axis is parallel to every middle
  /// axis (a planar shoulder–elbow–wrist, as on UR arms): the elbow is judged with a point of
  /// that axis as the wrist point.
  bool planar_elbow = false;
  /// Pairs of wrist joints whose axes can align (they are not parallel at every configuration).
  std::vector<std::pair<int, int>> wrist_pairs;
};

/// Geometric measures at one configuration, dimensionless, 0 at the singularity; NaN where the
/// arm lacks the part they need.
struct SingularityGeometry {
  /// Smallest ‖a_i × a_j‖ (sine of the angle) over `wrist_pairs`.
  double wrist_alignment = std::numeric_limits<double>::quiet_NaN();
  /// The pair reaching it (chain indices), −1 without one.
  int aligned_first = -1;
  int aligned_second = -1;
  /// How much an elbow joint can still change the shoulder–wrist distance: the largest, over the
  /// middle joints k, of |d·(a_k × (W − o_k))| / (‖d‖·‖W − o_k‖) with d = W − S: the sine of the
  /// elbow bend for a one-joint elbow. Needs S, and W or a planar elbow (W is then the anchor
  /// of the first wrist joint).
  double elbow_stretch = std::numeric_limits<double>::quiet_NaN();
  /// Distance of W from the first joint axis over ‖W − S‖ (‖W − o_0‖ without S). Needs W.
  double shoulder_offset = std::numeric_limits<double>::quiet_NaN();
  /// Shoulder centre S and wrist centre W in world coordinates [m] (NaN when absent).
  Eigen::Vector3d shoulder_centre =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d wrist_centre =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// When a configuration counts as singular, and when a kind is named.
struct SingularityThresholds {
  double sigma_min = 0.01;            ///< absolute: flagged when σmin < this
  double condition_number = 100.0;    ///< relative: flagged when σmax/σmin > this
  double geometric_tolerance = 0.05;  ///< a kind is named when its measure is below this
};

constexpr auto declared_fields(const SingularityThresholds*) {
  using S = SingularityThresholds;
  return declare<S>(
      "singularity thresholds",
      field("sigma_min", &S::sigma_min, "", Range::positive(), "flagged when σmin < this"),
      field("condition_number", &S::condition_number, "", Range::positive(),
            "flagged when σmax/σmin > this"),
      field("geometric_tolerance", &S::geometric_tolerance, "", Range::positive(),
            "a kind is named when its measure is below this"));
}

/// The classification of one configuration.
struct SingularityClassification {
  double sigma_min = 0.0;               ///< smallest singular value of the measured block
  double condition_number = 0.0;        ///< σmax/σmin (+infinity at an exact singularity)
  bool below_sigma_min = false;         ///< σmin < thresholds.sigma_min
  bool above_condition_number = false;  ///< σmax/σmin > thresholds.condition_number
  /// Empty when neither threshold is crossed; otherwise, in the order wrist, elbow, shoulder,
  /// the kinds whose measure is below the geometric tolerance and whose joints take part in the
  /// lost motions (the right singular vectors that cross a threshold, plus a redundant arm's
  /// self-motions): wrist the aligned pair, elbow the middle joints, shoulder the first joint.
  /// {unclassified} when none is.
  std::vector<SingularityKind> kinds;
  /// Right singular vector of σmin (unit, n entries, chain order, largest entry positive): the
  /// joint motion that moves the frame least. For a redundant arm it is orthogonal to the
  /// self-motion directions of the thin SVD.
  Eigen::VectorXd null_direction;
  SingularityGeometry geometry;
};

/// Classifies configurations of one chain; the arm's structure is found once at construction.
///
/// Kinds are judged on the full block only (6 rows [v; ω]): a position or orientation block
/// that crosses a threshold is reported `unclassified`, as is any arm without the parts a kind
/// needs (fewer than 6 hinges; no shoulder centre for elbow; no wrist centre for shoulder, nor
/// for elbow unless the elbow is planar).
class SingularityClassifier {
 public:
  /// @throws Error when the thresholds are not finite and positive, or @p measure is invalid.
  explicit SingularityClassifier(const Chain& chain, const ManipulabilityOptions& measure = {},
                                 const SingularityThresholds& thresholds = {});
  ~SingularityClassifier();
  SingularityClassifier(const SingularityClassifier& other);
  SingularityClassifier& operator=(const SingularityClassifier& other);
  SingularityClassifier(SingularityClassifier&& other) noexcept;
  SingularityClassifier& operator=(SingularityClassifier&& other) noexcept;

  const ArmStructure& structure() const noexcept { return structure_; }
  const SingularityThresholds& thresholds() const noexcept { return thresholds_; }
  /// The measure used (its result holds the last configuration classified).
  Manipulability& manipulability() noexcept { return manipulability_; }

  /// The geometric measures at @p q (chain order).
  /// @throws Error when @p q has the wrong size or holds NaN/inf.
  SingularityGeometry geometry(const Eigen::Ref<const Eigen::VectorXd>& q);

  /// Classifies @p q (chain order): thresholds, kinds and null direction. Allocates its result
  /// (a reporting tool, not for a control loop; `manipulability()` is the allocation-free test).
  /// @throws Error when @p q has the wrong size or holds NaN/inf.
  SingularityClassification classify(const Eigen::Ref<const Eigen::VectorXd>& q);

 private:
  SingularityGeometry measure_geometry() const;

  SingularityThresholds thresholds_;
  Manipulability manipulability_;
  ArmStructure structure_;
  struct Svd;  // the full-V SVD of the measured block (in the .cpp: Eigen/SVD)
  WorkspacePtr<Svd> svd_;
};

}  // namespace mjarm
