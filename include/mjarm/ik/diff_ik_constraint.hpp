#pragma once
/// @file
/// The interface of a `DiffIk` inequality constraint: rows C·v ≥ b on the joint velocity v, a
/// tightening of the velocity box, or both, recomputed at every step's configuration.

#include <Eigen/Core>

namespace mjarm {

/// A constraint of the differential-IK QP, evaluated once per `DiffIk::step()`.
///
/// General rows (`max_rows() > 0`) make `DiffIk` solve with the dense QP (qp::DenseQp); a
/// constraint that only tightens the box (`max_rows() == 0`) keeps the box QP. Every row has
/// the form of a barrier on a function h(q) that must stay ≥ 0:
///     ∇h(q)·v ≥ −gain·h(q)/dt,
/// so h may shrink by at most the fraction `gain` of what is left of it per step.
/// Implementations preallocate at construction: `rows()` and `tighten_box()` allocate nothing.
class DiffIkConstraint {
 public:
  virtual ~DiffIkConstraint() = default;

  /// Number of joint velocities (columns of every row): the chain's joint count.
  virtual int variables() const noexcept = 0;
  /// Most rows `rows()` ever writes (fixed at construction; 0: box only).
  virtual int max_rows() const noexcept = 0;

  /// Writes the active rows at configuration @p q (n, checked by the caller) into the first k
  /// rows of @p C (max_rows × n) and @p b (max_rows): C_r·v ≥ b_r. Returns k ≤ max_rows().
  virtual int rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                   Eigen::Ref<Eigen::MatrixXd> C, Eigen::Ref<Eigen::VectorXd> b) noexcept = 0;

  /// Tightens the velocity box [lo, hi] (n each) at @p q, staying inside it and never leaving
  /// it empty (a hard limit of the caller wins over this constraint). Default: nothing.
  virtual void tighten_box(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                           Eigen::Ref<Eigen::VectorXd> lo,
                           Eigen::Ref<Eigen::VectorXd> hi) const noexcept {
    (void)q;
    (void)dt;
    (void)lo;
    (void)hi;
  }

  /// Sets the joints outside the chain (full qpos, nq entries) for constraints that evaluate
  /// the model. Default: nothing.
  /// @throws Error for a wrong size or a non-finite value
  virtual void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) { (void)qpos; }
};

}  // namespace mjarm
