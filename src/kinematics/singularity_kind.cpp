#include "mjarm/kinematics/singularity_kind.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace mjarm {
namespace {

/// Axes meeting within this distance share a point [m] (the bundled models are exact to 1e-15).
constexpr double kAxesMeetTolerance = 1e-7;
/// Axes whose ‖a_i × a_j‖ stays below this at both probe configurations are parallel by design.
constexpr double kParallelByDesign = 1e-9;
/// A joint takes part in a lost motion when it moves by at least this much in some unit motion
/// of the lost directions.
constexpr double kInvolved = 0.1;

/// The point closest, in least squares, to the axes of chain joints @p joints (their world lines
/// at the last update of @p kin), and its largest distance to one of them. Empty when the axes
/// are (nearly) all parallel, so that no single point is closest.
std::optional<std::pair<Eigen::Vector3d, double>> closest_point_to_axes(
    const ChainKinematics& kin, const std::vector<int>& joints) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i : joints) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - kin.axis(i) * kin.axis(i).transpose();
    A += P;
    b += P * kin.anchor(i);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(A);
  if (!(eigen.eigenvalues()[0] > 1e-6)) return std::nullopt;
  const Eigen::Vector3d x = A.ldlt().solve(b);
  double residual = 0.0;
  for (int i : joints) {
    const Eigen::Vector3d r = x - kin.anchor(i);
    residual = std::max(residual, (r - kin.axis(i).dot(r) * kin.axis(i)).norm());
  }
  return std::make_pair(x, residual);
}

/// True when the axes of @p joints meet at one point at the last update of @p kin.
bool axes_meet(const ChainKinematics& kin, const std::vector<int>& joints) {
  const auto point = closest_point_to_axes(kin, joints);
  return point && point->second < kAxesMeetTolerance;
}

/// Distance of @p x from the axis of chain joint @p i [m].
double distance_to_axis(const ChainKinematics& kin, int i, const Eigen::Vector3d& x) {
  const Eigen::Vector3d r = x - kin.anchor(i);
  return (r - kin.axis(i).dot(r) * kin.axis(i)).norm();
}

/// How much the joints @p joints take part in the joint motions spanned by the columns of
/// @p directions (orthonormal): the largest norm of those entries over unit motions in the span.
double involvement(const Eigen::MatrixXd& directions, const std::vector<int>& joints) {
  if (directions.cols() == 0 || joints.empty()) return 0.0;
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(joints.size()), directions.cols());
  for (std::size_t k = 0; k < joints.size(); ++k) {
    rows.row(static_cast<Eigen::Index>(k)) = directions.row(joints[k]);
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(rows).singularValues()[0];
}

/// A second probe configuration: the centre moved by a few tenths of a radian per joint, with
/// alternating signs, clipped into the limits (so no accidental alignment of the centre stays).
Eigen::VectorXd second_probe(const Chain& chain) {
  Eigen::VectorXd q = chain.center();
  for (int i = 0; i < chain.size(); ++i) q[i] += (i % 2 == 0 ? 0.3 : -0.4) * (1 + i % 3);
  return chain.clamp(q);
}

}  // namespace

struct SingularityClassifier::Svd {
  // preallocated: classify() computes into it
  Svd(int rows, int cols) : svd(rows, cols, Eigen::ComputeFullV) {}
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
};

SingularityClassifier::SingularityClassifier(const Chain& chain,
                                             const ManipulabilityOptions& measure,
                                             const SingularityThresholds& thresholds)
    : thresholds_(thresholds), manipulability_(chain, measure) {
  check_fields(thresholds);
  const int n = chain.size();
  svd_ = make_workspace<Svd>(manipulability_.rows(), n);

  // the parts of the arm, from its axes at two configurations: a relation that holds at both is
  // one of the design (axes meeting at a joint centre, joints parallel by construction)
  ChainKinematics& kin = manipulability_.kinematics();
  const mjModel& m = chain.robot().model();
  bool hinges = n >= 6;
  kin.update(chain.center());
  for (int i = 0; i < n && hinges; ++i) {
    hinges = m.jnt_type[chain.joint_id(i)] == mjJNT_HINGE && kin.moves_frame(i);
  }
  if (!hinges) return;
  structure_.classifiable = true;
  structure_.wrist = {n - 3, n - 2, n - 1};
  const Eigen::VectorXd probes[2] = {chain.center(), second_probe(chain)};
  bool spherical = true;
  bool shoulder3 = n >= 7, shoulder2 = true;  // a shoulder leaves at least one middle joint
  const std::vector<int> first3 = {0, 1, 2}, first2 = {0, 1};
  std::vector<char> can_align(9, 0);
  for (const Eigen::VectorXd& q : probes) {
    kin.update(q);
    spherical = spherical && axes_meet(kin, structure_.wrist);
    shoulder3 = shoulder3 && axes_meet(kin, first3);
    shoulder2 = shoulder2 && axes_meet(kin, first2);
    for (int a = 0; a < 3; ++a) {
      for (int b = a + 1; b < 3; ++b) {
        const int i = structure_.wrist[a], j = structure_.wrist[b];
        if (kin.axis(i).cross(kin.axis(j)).norm() > kParallelByDesign) can_align[3 * a + b] = 1;
      }
    }
  }
  structure_.spherical_wrist = spherical;
  if (shoulder3 || shoulder2) {
    const int k = shoulder3 ? 3 : 2;
    for (int i = 0; i < k; ++i) structure_.shoulder.push_back(i);
    for (int i = k; i < n - 3; ++i) structure_.middle.push_back(i);
  }
  if (!spherical && !structure_.middle.empty()) {
    bool planar = true;
    for (const Eigen::VectorXd& q : probes) {
      kin.update(q);
      for (int k : structure_.middle) {
        planar = planar && kin.axis(k).cross(kin.axis(n - 3)).norm() < kParallelByDesign;
      }
    }
    structure_.planar_elbow = planar;
  }
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      if (can_align[3 * a + b]) {
        structure_.wrist_pairs.emplace_back(structure_.wrist[a], structure_.wrist[b]);
      }
    }
  }
}

SingularityClassifier::~SingularityClassifier() = default;
SingularityClassifier::SingularityClassifier(const SingularityClassifier& other) = default;
SingularityClassifier& SingularityClassifier::operator=(const SingularityClassifier& other) =
    default;
SingularityClassifier::SingularityClassifier(SingularityClassifier&& other) noexcept = default;
SingularityClassifier& SingularityClassifier::operator=(SingularityClassifier&& other) noexcept =
    default;

SingularityGeometry SingularityClassifier::geometry(const Eigen::Ref<const Eigen::VectorXd>& q) {
  manipulability_.chain().check(q, "q");
  manipulability_.kinematics().update(q);
  return measure_geometry();
}

SingularityGeometry SingularityClassifier::measure_geometry() const {
  SingularityGeometry g;
  if (!structure_.classifiable) return g;
  const ChainKinematics& kin = manipulability_.kinematics();
  // wrist: the two wrist axes closest to parallel
  for (const auto& [i, j] : structure_.wrist_pairs) {
    const double s = kin.axis(i).cross(kin.axis(j)).norm();
    if (!(s >= g.wrist_alignment)) {
      g.wrist_alignment = s;
      g.aligned_first = i;
      g.aligned_second = j;
    }
  }
  // centres: the points the shoulder and the wrist axes meet at
  if (structure_.spherical_wrist) {
    if (const auto w = closest_point_to_axes(kin, structure_.wrist)) g.wrist_centre = w->first;
  }
  if (!structure_.shoulder.empty()) {
    if (const auto s = closest_point_to_axes(kin, structure_.shoulder)) {
      g.shoulder_centre = s->first;
    }
  }
  // the wrist point: the wrist centre, or on a planar elbow a point of the first wrist axis
  // (the elbow measure only sees the plane perpendicular to the parallel axes)
  const Eigen::Vector3d W =
      structure_.planar_elbow ? kin.anchor(structure_.wrist[0]) : g.wrist_centre;
  const Eigen::Vector3d& S = g.shoulder_centre;
  if (!W.allFinite()) return g;
  // elbow: can any middle joint still change the shoulder–wrist distance?
  const Eigen::Vector3d d = W - S;
  if (S.allFinite() && !structure_.middle.empty() && d.norm() > kAxesMeetTolerance) {
    double stretch = 0.0;
    for (int k : structure_.middle) {
      const Eigen::Vector3d lever = W - kin.anchor(k);
      if (lever.norm() <= kAxesMeetTolerance) continue;
      stretch =
          std::max(stretch, std::abs(d.dot(kin.axis(k).cross(lever))) / (d.norm() * lever.norm()));
    }
    g.elbow_stretch = stretch;
  }
  // shoulder: the wrist centre on the first axis
  if (!structure_.spherical_wrist) return g;
  const double reach = S.allFinite() ? d.norm() : (W - kin.anchor(0)).norm();
  if (reach > kAxesMeetTolerance) g.shoulder_offset = distance_to_axis(kin, 0, W) / reach;
  return g;
}

SingularityClassification SingularityClassifier::classify(
    const Eigen::Ref<const Eigen::VectorXd>& q) {
  const ManipulabilityResult& r = manipulability_.evaluate(q);
  SingularityClassification c;
  c.sigma_min = r.sigma_min;
  c.condition_number = r.condition_number;
  c.below_sigma_min = r.sigma_min < thresholds_.sigma_min;
  c.above_condition_number = r.condition_number > thresholds_.condition_number;
  c.geometry = measure_geometry();
  // the joint motion that moves the frame least, with a sign fixed by its largest entry
  svd_->svd.compute(manipulability_.jacobian_block());
  const Eigen::VectorXd& sigma = svd_->svd.singularValues();
  const Eigen::Index p = sigma.size(), n = svd_->svd.matrixV().cols();
  c.null_direction = svd_->svd.matrixV().col(p - 1);
  Eigen::Index largest = 0;
  c.null_direction.cwiseAbs().maxCoeff(&largest);
  if (c.null_direction[largest] < 0.0) c.null_direction = -c.null_direction;
  if (!c.below_sigma_min && !c.above_condition_number) return c;

  // the joint motions lost or nearly lost: every singular direction that crosses a threshold,
  // and a redundant arm's self-motions (n > rows), which the SVD mixes with them
  Eigen::Index first = p - 1;
  while (first > 0 && (sigma[first - 1] < thresholds_.sigma_min ||
                       sigma[0] > thresholds_.condition_number * sigma[first - 1])) {
    --first;
  }
  const Eigen::MatrixXd lost = svd_->svd.matrixV().rightCols(n - first);

  // kinds are judged on the full Jacobian only: the geometry speaks of motion and orientation;
  // a kind is named when its geometry holds and the lost motions involve its joints
  const bool full = manipulability_.options().block == JacobianBlock::full;
  const double tol = thresholds_.geometric_tolerance;
  const SingularityGeometry& g = c.geometry;
  if (full && g.wrist_alignment < tol && involvement(lost, {g.aligned_first}) >= kInvolved &&
      involvement(lost, {g.aligned_second}) >= kInvolved) {
    c.kinds.push_back(SingularityKind::wrist);
  }
  if (full && g.elbow_stretch < tol && involvement(lost, structure_.middle) >= kInvolved) {
    c.kinds.push_back(SingularityKind::elbow);
  }
  if (full && g.shoulder_offset < tol && involvement(lost, {0}) >= kInvolved) {
    c.kinds.push_back(SingularityKind::shoulder);
  }
  if (c.kinds.empty()) c.kinds.push_back(SingularityKind::unclassified);
  return c;
}

}  // namespace mjarm
