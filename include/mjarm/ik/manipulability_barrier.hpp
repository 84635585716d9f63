#pragma once
/// @file
/// A singularity barrier for the differential-IK QP: one row keeping the Yoshikawa
/// manipulability w(q) of the chain's frame above `min_manipulability`,
///
///     ∇w(q)·v ≥ −gain·(w(q) − min_manipulability)/dt,
///
/// with the analytic gradient of `Manipulability`. A hard row, not a soft task: near w_min the
/// step may only move along directions that do not lose manipulability (to first order). At an
/// exact singularity ∇w is set to 0 (w is not differentiable there) and the row is dropped.

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/ik/diff_ik_constraint.hpp"
#include "mjarm/kinematics/manipulability.hpp"

namespace mjarm {

/// Which manipulability is kept, above what, and how fast it may fall.
struct ManipulabilityBarrierOptions {
  JacobianBlock block = JacobianBlock::position;  ///< rows of J measured
  double min_manipulability = 1e-3;  ///< w_min (> 0, units of w: m³ for the position block)
  double gain = 0.5;                 ///< fraction of w − w_min one step may lose, (0, 1]
};

constexpr auto declared_fields(const ManipulabilityBarrierOptions*) {
  using S = ManipulabilityBarrierOptions;
  return declare<S>("manipulability barrier", field("block", &S::block, "rows of J measured"),
                    field("min_manipulability", &S::min_manipulability, "", Range::positive(),
                          "manipulability kept above this"),
                    field("gain", &S::gain, "", Range::open_closed(0.0, 1.0),
                          "fraction of w − w_min one step may lose"));
}

/// The manipulability row of a chain's differential IK (see the file comment). Joints outside
/// the chain follow `set_fixed_qpos` (the model's qpos0 by default).
class ManipulabilityBarrier final : public DiffIkConstraint {
 public:
  /// @throws Error for an invalid option.
  ManipulabilityBarrier(const Chain& chain, const ManipulabilityBarrierOptions& options);

  const ManipulabilityBarrierOptions& options() const noexcept { return options_; }
  /// The manipulability of the last `rows()` call.
  double manipulability() const noexcept { return manip_.result().manipulability; }

  int variables() const noexcept override { return static_cast<int>(gradient_.size()); }
  int max_rows() const noexcept override { return 1; }
  int rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt, Eigen::Ref<Eigen::MatrixXd> C,
           Eigen::Ref<Eigen::VectorXd> b) noexcept override;
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) override;

 private:
  ManipulabilityBarrierOptions options_;
  Manipulability manip_;
  Eigen::VectorXd gradient_;
};

}  // namespace mjarm
