#pragma once
/// @file
/// `CollisionChecker`: the cheapest check a sampling-based planner asks millions of times — is
/// configuration q within the joint ranges and free of counted contacts (`RobotContacts`)? —
/// on an owned scratch `mjData` with MuJoCo's kinematics and collision detection only.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/planning/robot_contacts.hpp"

namespace mjarm {

/// Judges configurations of one chain: joint ranges (within 1e-9), then `mj_kinematics` and
/// `mj_collision` (no inertia, no velocities: the rest of `mj_forward` does not change a contact)
/// and the deepest counted contact below the margin. Not thread-safe (one scratch `mjData`).
class CollisionChecker {
 public:
  /// @param margin a contact counts below this signed distance [m] (≥ 0)
  /// @throws Error for a negative or non-finite margin.
  explicit CollisionChecker(const Chain& chain, double margin = 0.0);

  const Chain& chain() const noexcept { return chain_; }
  /// The contact filter: allow pairs on it (`RobotContacts::allow`).
  RobotContacts& contacts() noexcept { return contacts_; }
  const RobotContacts& contacts() const noexcept { return contacts_; }

  /// Sets the joints that are not in the chain (full qpos, nq entries; default qpos0).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// True when q (n values, unchecked count) is finite, within the joint ranges and touches
  /// nothing. Allocates nothing, never throws; counts one check.
  bool valid(const double* q) noexcept;
  bool valid(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept { return valid(q.data()); }

  /// The deepest counted contact of the last `valid` call (none when it failed on the ranges).
  const RobotContact& last_contact() const noexcept { return last_; }
  /// Index of the joint outside its range at the last call (−1: none).
  int last_limit_joint() const noexcept { return limit_joint_; }
  /// Why the last `valid` call said no, in words ("ok" when it said yes).
  std::string describe_last() const;

  /// States judged since construction or the last reset.
  std::int64_t checks() const noexcept { return checks_; }
  void reset_checks() noexcept { checks_ = 0; }

 private:
  Chain chain_;
  RobotContacts contacts_;
  double margin_;
  DataPtr data_;
  Eigen::VectorXd fixed_qpos_;
  RobotContact last_;
  int limit_joint_ = -1;
  bool finite_ = true;
  std::int64_t checks_ = 0;
};

}  // namespace mjarm
