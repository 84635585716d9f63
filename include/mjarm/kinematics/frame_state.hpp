#pragma once
/// @file
/// A frame's state read from MuJoCo's own `mjData`: its pose and MuJoCo's world-aligned Jacobian
/// restricted to a chain's joints. These are the reference the faster `ChainKinematics` is checked
/// and benchmarked against. Also a checked one-call forward kinematics for one-off use.

#include <mujoco/mujoco.h>

#include <Eigen/Core>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// The pose X_WF of @p frame (a site or a body) read from @p d: `site_xpos`/`site_xmat` for a
/// site, `xpos`/`xmat` for a body (the body frame, not its inertial frame). @p d must hold
/// positions computed by `mj_kinematics` (or `mj_forward`/`mj_step`).
/// @throws Error when the frame id is out of range for @p m.
Pose frame_pose(const mjModel& m, const mjData& d, const FrameRef& frame);

/// MuJoCo's world-aligned Jacobian of the chain's frame (`mj_jacSite` for a site, `mj_jacBody`
/// for a body), restricted to the chain's degrees of freedom: column i is chain joint i. Rows are
/// linear first: rows 0–2 the velocity of the frame origin [m/s per rad or m/s per m/s], rows
/// 3–5 the angular velocity [rad/s per unit joint velocity], both in world axes.
///
/// @p d must hold `mj_kinematics` and `mj_comPos` results (e.g. after `mj_forward`) for the
/// configuration of interest. Uses a per-thread scratch buffer of 6·nv values, which allocates
/// only when a larger model is met on that thread.
/// @param J output, 6 × chain.size().
/// @throws Error when @p J does not have 6 rows and chain.size() columns.
void mujoco_frame_jacobian(const Chain& chain, const mjData& d, Eigen::Ref<Matrix6Xd> J);

/// The pose X_WE of the chain's frame at joint values @p q (chain order, chain.size() values),
/// with joints outside the chain at the model's reference configuration qpos0. Builds a
/// `ChainKinematics` on each call: for repeated evaluation keep a `ChainKinematics` instead.
/// @throws Error when @p q has the wrong size or holds NaN/inf (via `Chain::check`).
Pose forward_kinematics(const Chain& chain, const Eigen::VectorXd& q);

}  // namespace mjarm
