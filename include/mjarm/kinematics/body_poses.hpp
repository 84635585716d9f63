#pragma once
/// @file
/// Forward kinematics of every body at once (each link's frame, not only the end frame), from
/// joint values, on a scratch `mjData` of its own: nothing the caller owns is touched.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// World poses of all bodies of a robot (body 0 is the world), by MuJoCo's `mj_kinematics`.
/// Allocation-free after construction.
class BodyPoses {
 public:
  explicit BodyPoses(const Robot& robot);

  /// The poses at the full configuration @p qpos (nq values; mocap bodies at the model's poses).
  /// @throws Error for a wrong size or a value that is not finite.
  void update(const Eigen::Ref<const Eigen::VectorXd>& qpos);
  /// The poses at @p chain's joint values @p q (chain order), the other joints at qpos0.
  /// @throws Error for a chain of another model, a wrong size or a value that is not finite.
  void update(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q);

  /// The number of bodies (nbody, the world included).
  int size() const noexcept { return static_cast<int>(poses_.size()); }
  /// The pose X_WB of body @p id at the last update.
  const Pose& pose(int id) const { return poses_.at(static_cast<std::size_t>(id)); }
  /// The pose X_WB of the body called @p name.
  /// @throws Error naming the body with the closest names.
  const Pose& pose(std::string_view name) const;
  /// All poses, in body id order.
  const std::vector<Pose>& poses() const noexcept { return poses_; }
  /// The bodies' names in id order ("world" first, "" for an unnamed body).
  const std::vector<std::string>& names() const noexcept { return names_; }

 private:
  void compute() noexcept;

  Robot robot_;
  DataPtr data_;
  std::vector<Pose> poses_;
  std::vector<std::string> names_;
};

}  // namespace mjarm
