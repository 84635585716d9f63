#pragma once
/// @file
/// Forward kinematics and Jacobians of one chain, evaluated on the chain's own bodies only, so
/// that the cost does not grow with the rest of the scene.

#include <Eigen/Core>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm {

/// A 6×n Jacobian, rows linear first `[v; ω]`.
using Matrix6Xd = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// How the rows of a frame Jacobian are expressed.
enum class JacobianFrame {
  world_aligned,  ///< velocity of the frame origin and angular velocity, in world axes (MuJoCo's mj_jacSite)
  local,          ///< the same twist in the frame's own axes (body twist V_E)
  world           ///< spatial twist: velocity of the point at the world origin moving with E
};

constexpr auto declared_names(const JacobianFrame*) {
  using F = JacobianFrame;
  return std::array{
      EnumName{F::world_aligned, "world_aligned",
               "velocity of the frame origin and angular velocity, world axes (mj_jacSite)"},
      EnumName{F::local, "local", "the same twist in the frame's axes (body twist)"},
      EnumName{F::world, "world", "spatial twist (point at the world origin)"}};
}

/// Forward kinematics of a `Chain`, with preallocated workspace: `update()` and `jacobian()`
/// allocate nothing. Joints of the model outside the chain but on the frame's path hold the
/// configuration given by `set_fixed_qpos` (the model's qpos0 by default).
///
/// Results agree with MuJoCo's `mj_kinematics` + `mj_jacSite` to ~1e-15.
class ChainKinematics {
 public:
  /// @throws Error when the chain's model has no movable joints on the path (from Chain).
  explicit ChainKinematics(const Chain& chain);

  const Chain& chain() const noexcept { return chain_; }

  /// Sets the configuration of the joints that are not in the chain (full qpos, nq entries).
  /// @throws Error when the size is not nq or a value is not finite.
  void set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos);

  /// Computes the pose X_WE of the chain's frame at joint values @p q (chain order, size n) and
  /// the joint axes used by `jacobian()`. Unchecked: validate q with `Chain::check` first.
  /// The same q as the last call (bit for bit, fixed joints unchanged) returns the last result
  /// without recomputing it, so two users of one instance at one q pay once.
  const Pose& update(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept;

  /// Pose X_WE from the last `update()`.
  const Pose& pose() const noexcept { return X_WE_; }

  /// The 6×n frame Jacobian at the last `update()`, written into @p J (must be 6×n).
  void jacobian(Eigen::Ref<Matrix6Xd> J, JacobianFrame frame = JacobianFrame::world_aligned) const noexcept;

  /// World axis of chain joint i at the last `update()` (unit vector).
  const Eigen::Vector3d& axis(int i) const noexcept { return axes_[i]; }
  /// World anchor point of chain joint i at the last `update()` [m].
  const Eigen::Vector3d& anchor(int i) const noexcept { return anchors_[i]; }
  /// Whether chain joint i moves the frame (false for joints off the frame's path).
  bool moves_frame(int i) const noexcept { return on_path_[i]; }

  /// The bias acceleration J̇·q̇ of the frame (world-aligned, linear first) at the last
  /// `update()`, for joint velocities @p qd (size n): on the chain's path only, where
  /// MuJoCo's `mj_jacDot` needs the whole tree's velocities (mj_comVel) first.
  Vector6d bias_acceleration(const Eigen::Ref<const Eigen::VectorXd>& qd) const noexcept;

 private:
  /// One joint met on the path from the world to the frame, in path order.
  struct PathJoint {
    int type = 0;            // mjtJoint
    Eigen::Vector3d axis;    // in the body frame
    Eigen::Vector3d pos;     // anchor in the body frame
    double qpos0 = 0.0;      // reference value (hinge/slide)
    int chain_index = -1;    // index in the chain, or -1 when held fixed
    int qpos_address = 0;
    int unit_axis = -1;      // k when axis is exactly ±e_k (then a two-column rotation), else -1
    double unit_sign = 1.0;  // the sign of that axis
    bool at_origin = false;  // pos is exactly zero (the anchor is the body origin)
  };
  /// One body on the path, with its joints.
  struct PathBody {
    Eigen::Vector3d pos;     // in the parent body frame
    Eigen::Matrix3d rot;     // R_parent,body
    int first_joint = 0;     // into joints_
    int joint_count = 0;
    bool free_root = false;  // pose comes straight from a free joint's qpos
  };

  Chain chain_;
  std::vector<PathBody> bodies_;
  std::vector<PathJoint> joints_;
  Eigen::VectorXd fixed_qpos_;
  Eigen::Vector3d frame_pos_;  // frame in its body
  Eigen::Matrix3d frame_rot_;
  // workspace
  Pose X_WE_;
  Eigen::VectorXd last_q_;  // q of the last update (size n)
  bool current_ = false;    // X_WE_, axes_ and anchors_ belong to last_q_
  std::vector<Eigen::Vector3d> axes_;
  std::vector<Eigen::Vector3d> anchors_;
  std::vector<char> on_path_;
  std::vector<int> path_order_;  // chain indices of path joints in path order
};

}  // namespace mjarm
