#pragma once
/// @file
/// Collision avoidance as inequality rows of the differential-IK QP: for chosen geom pairs, the
/// signed distance d stays above `min_distance`, approaching it no faster than `gain` times the
/// remaining margin per step:
///
///     J_d·v ≥ −gain·(d − min_distance)/dt,    J_d = n̂ᵀ(J_p(p₂) − J_p(p₁)),
///
/// p₁, p₂ the nearest points of the two geoms (MuJoCo's narrow phase, `mj_geomDistance`), n̂ the
/// unit normal from geom 1 to geom 2 and J_p(p) the translational Jacobian of the point p
/// attached to its geom's body (`mj_jac`), restricted to the chain's joints. Only pairs closer
/// than `detection_distance` become rows. Everything is evaluated on an owned scratch `mjData`.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/ik/diff_ik_constraint.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Which geom pairs must keep apart, and how.
struct CollisionAvoidanceOptions {
  /// Geom pairs (names), checked whatever the model's contype/conaffinity/exclude filters say.
  std::vector<std::pair<std::string, std::string>> pairs;
  /// Adds every robot geom against every scene geom: robot geoms are the collision geoms
  /// (contype or conaffinity non-zero) on bodies moved by the chain's joints; scene geoms are
  /// the collision geoms outside the robot's kinematic tree (world geoms and other trees).
  bool robot_vs_scene = false;
  /// Smallest signed distance allowed [m] (≥ 0).
  double min_distance = 0.005;
  /// Pairs closer than this become rows [m] (> min_distance).
  double detection_distance = 0.05;
  /// Fraction of the remaining margin d − min_distance that one step may close, (0, 1].
  double gain = 0.5;
};

constexpr auto declared_fields(const CollisionAvoidanceOptions*) {
  using S = CollisionAvoidanceOptions;
  return declare<S>(
      "collision avoidance", field("pairs", &S::pairs, "geom name pairs that must keep apart"),
      field("robot_vs_scene", &S::robot_vs_scene,
            "every geom moved by the chain against every geom outside the robot's tree"),
      field("min_distance", &S::min_distance, "m", Range::non_negative(),
            "smallest signed distance allowed"),
      field("detection_distance", &S::detection_distance, "m", Range::positive(),
            "pairs closer than this become rows (> min_distance)"),
      field("gain", &S::gain, "", Range::open_closed(0.0, 1.0),
            "fraction of the remaining margin one step may close"));
}

/// The collision rows of a chain's differential IK (see the file comment). Joints outside the
/// chain hold the configuration given by `set_fixed_qpos` (the model's qpos0 by default).
class CollisionAvoidance final : public DiffIkConstraint {
 public:
  /// Resolves the geom names and preallocates for every pair.
  /// @throws Error naming an unknown geom (with the closest names), a pair of a geom with
  /// itself, an invalid option, or no pair at all.
  CollisionAvoidance(const Chain& chain, const CollisionAvoidanceOptions& options);

  const CollisionAvoidanceOptions& options() const noexcept { return options_; }
  /// Number of watched pairs (the most rows).
  int pair_count() const noexcept { return static_cast<int>(pairs_.size()); }
  /// Geom ids of watched pair @p i.
  std::pair<int, int> pair(int i) const { return pairs_.at(i); }

  int variables() const noexcept override { return chain_.size(); }
  int max_rows() const noexcept override { return pair_count(); }
  int rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt, Eigen::Ref<Eigen::MatrixXd> C,
           Eigen::Ref<Eigen::VectorXd> b) noexcept override;
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) override;

  /// Signed distance of pair @p i at @p q (n, unchecked) [m], capped at `detection_distance`.
  double distance(const Eigen::Ref<const Eigen::VectorXd>& q, int i) noexcept;
  /// The pair behind row @p r of the last `rows()` call.
  int row_pair(int r) const { return row_pair_.at(r); }
  /// Distance of row @p r's pair at the last `rows()` call [m].
  double row_distance(int r) const { return row_distance_.at(r); }
  /// Smallest distance over all pairs at the last `rows()` call [m] (capped at
  /// `detection_distance`).
  double min_distance_seen() const noexcept { return min_seen_; }

 private:
  void place(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept;
  /// Distance of geoms g1, g2 on the placed data, nearest points in fromto (when closer than
  /// the detection distance).
  double pair_distance(int g1, int g2, double fromto[6]) noexcept;
  /// Writes J_d (n) of the pair with nearest points fromto and signed distance d.
  void distance_jacobian(int g1, int g2, const double fromto[6], double d,
                         Eigen::VectorXd& row) noexcept;

  Chain chain_;
  CollisionAvoidanceOptions options_;
  std::vector<std::pair<int, int>> pairs_;
  DataPtr data_;
  Eigen::VectorXd fixed_qpos_;
  // workspace: 3×nv Jacobians of the two nearest points (row-major, as mj_jac writes them)
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> jac1_, jac2_;
  Eigen::VectorXd jd_;  // J_d of the pair at hand (n)
  std::vector<int> row_pair_;
  std::vector<double> row_distance_;
  double min_seen_ = 0.0;
};

}  // namespace mjarm
