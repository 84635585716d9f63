#pragma once
/// @file
/// `ChainDynamics`: the joint-space dynamics of one chain, read from an up-to-date `mjData`
/// without writing to it: mass matrix, bias forces, gravity torques, the end-effector Jacobian
/// and its bias acceleration J̇·q̇, and inverse dynamics τ = M·q̈ + h.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// Joint-space dynamics of a `Chain`, restricted to the chain's degrees of freedom (index i =
/// chain joint i, n = chain.size()). The equation of motion of those dofs, with every other dof
/// held at zero acceleration, reads
///
///     M(q)·q̈ + h(q, q̇) = τ + τ_passive + τ_constraint,   h = C(q, q̇)·q̇ + g(q)
///
/// `update()` reads a state whose kinematics and dynamics are already computed (after
/// `mj_forward`, or `mj_step1` in a split step): M, qfrc_bias, subtree_com, xaxis, xanchor,
/// cdof_dot, cvel, site/body poses. It never writes to that `mjData`, never runs a scratch
/// pipeline, and allocates nothing after construction.
///
/// Units: M in kg·m² (hinge) or kg (slide), h and g in N·m or N, J rows linear first [v; ω] in
/// world axes (MuJoCo's `mj_jacSite` layout), J̇·q̇ in m/s² and rad/s².
class ChainDynamics {
 public:
  /// Preallocates every buffer for @p chain (copied; it shares the immutable model).
  /// @throws Error when the chain holds a joint that is not a hinge or a slide (from Chain).
  explicit ChainDynamics(const Chain& chain);

  /// The chain the dynamics are restricted to.
  const Chain& chain() const noexcept { return chain_; }
  /// Number of chain dofs n.
  int size() const noexcept { return chain_.size(); }

  /// Reads everything below from @p d (same model as the chain; state already computed).
  /// Never writes @p d, never allocates.
  void update(const mjData& d) noexcept;

  /// Chain joint positions q [rad or m] at the last `update()` (n).
  const Eigen::VectorXd& q() const noexcept { return q_; }
  /// Chain joint velocities q̇ [rad/s or m/s] at the last `update()` (n).
  const Eigen::VectorXd& qd() const noexcept { return qd_; }

  /// Joint-space inertia M (n×n, symmetric positive definite, armature included) — the
  /// chain's rows and columns of MuJoCo's M [kg·m² or kg].
  const Eigen::MatrixXd& mass_matrix() const noexcept { return M_; }

  /// Bias forces h = C(q, q̇)·q̇ + g(q) on the chain's dofs (MuJoCo's qfrc_bias) [N·m or N].
  /// Passive forces (joint damping, springs) are not part of h: they are in qfrc_passive.
  const Eigen::VectorXd& bias() const noexcept { return h_; }

  /// Gravity torques g(q) (the torques that hold the arm still against gravity) [N·m or N],
  /// from each joint's subtree mass and centre of mass: hinge j, axis a_j at anchor o_j:
  /// g_j = −m_sub·(a_j × (c_sub − o_j))·gravity; slide j: g_j = −m_sub·a_j·gravity.
  /// Zero when the model disables gravity.
  const Eigen::VectorXd& gravity() const noexcept { return g_; }

  /// Pose X_WE of the chain's frame at the last `update()` (site or body frame).
  const Pose& pose() const noexcept { return X_WE_; }

  /// World-aligned Jacobian J_WE (6×n, linear first): rows 0–2 the velocity of E's origin in
  /// world axes, rows 3–5 E's angular velocity. Columns of joints off E's path are zero.
  const Matrix6Xd& jacobian() const noexcept { return J_; }

  /// Spatial velocity V_WE = [v; ω] of E (world axes, linear first) from the full qvel [m/s,
  /// rad/s]; equals J·q̇ when only chain joints move.
  const Vector6d& velocity() const noexcept { return V_WE_; }

  /// Bias acceleration J̇·q̇ of E (world-aligned, linear first) [m/s², rad/s²]: the acceleration
  /// of E's origin and E's angular acceleration when every dof has zero acceleration, so that
  /// A_WE = J·q̈ + J̇·q̇. Uses the velocities of every joint on E's path (not only the chain's).
  const Vector6d& bias_acceleration() const noexcept { return Jdot_qd_; }

  /// Inverse dynamics on the chain's dofs: τ = M·q̈ + h, with q̈ on the chain's dofs and zero on
  /// every other dof, computed with MuJoCo's sparse `mj_mulM` and qfrc_bias of @p d (which must
  /// be the same up-to-date state; `update()` is not needed first). Passive and constraint
  /// forces are not included (mj_inverse's qfrc_inverse = this − qfrc_passive − qfrc_constraint).
  /// Unchecked sizes: @p qdd and @p tau have n entries. Never writes @p d, never allocates.
  void inverse_dynamics(const mjData& d, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                        Eigen::Ref<Eigen::VectorXd> tau) noexcept;

 private:
  /// One stored entry of MuJoCo's sparse M that falls inside the chain block.
  struct MassEntry {
    int row = 0;      // chain index
    int col = 0;      // chain index
    int address = 0;  // into mjData::M
  };
  Chain chain_;
  std::vector<MassEntry> mass_entries_;
  std::vector<int> path_dofs_;         // dofs of every joint on E's path, root first
  std::vector<int> chain_on_path_;     // 1 when chain joint i moves E
  std::vector<int> joint_body_;        // body moved by chain joint i
  std::vector<double> subtree_mass_;   // subtree mass of that body [kg]
  int frame_body_ = 0;
  int root_body_ = 0;                  // root of E's kinematic tree (com-based vectors' origin)
  // workspace
  Eigen::VectorXd q_;
  Eigen::VectorXd qd_;
  Eigen::MatrixXd M_;
  Eigen::VectorXd h_;
  Eigen::VectorXd g_;
  Pose X_WE_;
  Matrix6Xd J_;
  Vector6d V_WE_ = Vector6d::Zero();
  Vector6d Jdot_qd_ = Vector6d::Zero();
  Eigen::VectorXd qacc_full_;  // nv
  Eigen::VectorXd force_full_; // nv
};

}  // namespace mjarm
