#pragma once
/// @file
/// `Chain`: the joints an algorithm moves and the end-effector frame it controls.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/model/robot.hpp"

namespace mjarm {

/// What the end-effector frame is attached to.
enum class FrameKind { site, body };

/// An end-effector frame: a site or a body of the model.
struct FrameRef {
  FrameKind kind = FrameKind::site;
  int id = 0;
  std::string name;
};

/// Finds the frame called @p name: a site first, then a body.
/// @throws Error listing the closest site and body names when neither exists.
FrameRef find_frame(const Robot& robot, std::string_view name);

/// The joints an algorithm moves, in order (index i = column i of a Jacobian), and the
/// end-effector frame. Only hinge and slide joints can be moved; joints of the model outside the
/// chain are held where the caller puts them.
class Chain {
 public:
  /// Every hinge and slide joint on the path from the world to @p frame (a site or body name).
  /// Free and ball joints on the path are not moved (they hold their configuration).
  /// @throws Error when the frame is unknown or no movable joint lies on its path.
  Chain(const Robot& robot, std::string_view frame);

  /// An explicit list of joints moving @p frame (joints off the frame's path are allowed: they
  /// give zero Jacobian columns).
  /// @throws Error for unknown names, repeated joints, or ball/free joints.
  Chain(const Robot& robot, const std::vector<std::string>& joints, std::string_view frame);

  const Robot& robot() const noexcept { return robot_; }
  const FrameRef& frame() const noexcept { return frame_; }
  /// Number of joints (= degrees of freedom) moved.
  int size() const noexcept { return static_cast<int>(joints_.size()); }

  int joint_id(int i) const { return joints_.at(i); }
  const std::vector<int>& joint_ids() const noexcept { return joints_; }
  const std::vector<std::string>& joint_names() const noexcept { return names_; }
  int qpos_address(int i) const { return qpos_addresses_.at(i); }
  int dof_address(int i) const { return dof_addresses_.at(i); }
  const std::vector<int>& dof_addresses() const noexcept { return dof_addresses_; }
  /// The actuator driving joint i, if any (the first one found).
  std::optional<int> actuator(int i) const { return actuators_.at(i); }
  /// Joint ids on the path from the world to the frame that the chain does not move (free and
  /// ball joints, or hinge and slide joints left out of an explicit list), root first. Empty when
  /// the chain holds every joint of the path: then the frame hangs from a fixed base.
  std::vector<int> unmoved_path_joints() const;

  /// Joint bounds [rad or m]; unlimited joints give ∓infinity.
  const Eigen::VectorXd& lower() const noexcept { return lower_; }
  const Eigen::VectorXd& upper() const noexcept { return upper_; }
  /// Middle of the range (0 for unlimited joints).
  Eigen::VectorXd center() const;
  /// True when every joint is inside its bounds widened by @p tolerance.
  bool within_limits(const Eigen::Ref<const Eigen::VectorXd>& q, double tolerance = 0.0) const;
  /// @p q clipped into the bounds.
  Eigen::VectorXd clamp(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  /// @throws Error when @p q does not have size() entries or holds NaN/inf; @p what names it.
  void check(const Eigen::Ref<const Eigen::VectorXd>& q, std::string_view what = "q") const;
  /// @throws Error when @p qpos is not a full configuration of the model (nq entries, all
  /// finite); @p what names it.
  void check_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos,
                  std::string_view what = "qpos") const;

  /// The chain's joint values taken from a full qpos (nq entries).
  Eigen::VectorXd gather(const double* qpos) const;
  /// Writes the chain's joint values into a full qpos (nq entries).
  void scatter(const Eigen::Ref<const Eigen::VectorXd>& q, double* qpos) const noexcept;

 private:
  void add_joint(int id);
  void finish();

  Robot robot_;
  FrameRef frame_;
  std::vector<int> joints_;
  std::vector<std::string> names_;
  std::vector<int> qpos_addresses_;
  std::vector<int> dof_addresses_;
  std::vector<std::optional<int>> actuators_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
};

}  // namespace mjarm
