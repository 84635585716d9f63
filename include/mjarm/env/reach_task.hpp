#pragma once
/// @file
/// `ReachTask`: bring the end effector to a random point, with a dense reward.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/env/env_task.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Settings of a `ReachTask` (defaults: the Panda).
struct ReachOptions {
  /// The robot: a bundled torque-motor model or an MJCF file. It is composed into a scene
  /// (`Scene`) as robot "arm", with a floor and a force and a torque sensor on @p frame
  /// ("arm/ft_force", "arm/ft_torque"), so its names carry the prefix "arm/".
  std::string model = "panda_torque";
  std::string frame = "attachment_site";  ///< the end effector (a site or body of the model)
  std::string keyframe = "home";          ///< the start configuration (qpos0 when empty)
  double start_perturbation = 0.05;       ///< each joint starts at keyframe ± this, uniform [rad]
  /// Targets are drawn uniformly in the box centre ± half_width (world, m).
  Eigen::Vector3d target_center = Eigen::Vector3d(0.45, 0.0, 0.45);
  Eigen::Vector3d target_half_width = Eigen::Vector3d(0.15, 0.25, 0.15);
  /// The episode terminates (success, discount 0) once ‖p_WE − p_T‖ ≤ this [m]; 0: never.
  double success_distance = 0.01;
};

constexpr auto declared_fields(const ReachOptions*) {
  using S = ReachOptions;
  return declare<S>("reach",
                    field("model", &S::model, "a bundled torque-motor model or an MJCF file"),
                    field("frame", &S::frame, "the end effector (a site or body of the model)"),
                    field("keyframe", &S::keyframe, "the start configuration (qpos0 when empty)"),
                    field("start_perturbation", &S::start_perturbation, "rad",
                          Range::non_negative(), "each joint starts at keyframe ± this, uniform"),
                    field("target_center", &S::target_center, "m", Range::finite(),
                          "centre of the targets' box (world)"),
                    field("target_half_width", &S::target_half_width, "m", Range::non_negative(),
                          "half widths of the targets' box"),
                    field("success_distance", &S::success_distance, "m", Range::non_negative(),
                          "terminate once the tip is this close; 0: never"));
}

/// Reach: the end effector E starts at the keyframe (each joint perturbed) and should reach a
/// target point T drawn at every episode. Reward r = −‖p_WE − p_T‖ [m] per step (dense);
/// terminates when the distance is within `success_distance`. Observations of its own:
/// `target` (3, the box's bounds), `target_offset` (p_T − p_WE, 3). The episode's task
/// generator draws the start offsets (one per joint, in chain order), then the target (x, y, z).
class ReachTask final : public EnvTask {
 public:
  /// @throws Error for an unknown model, frame or keyframe, a non-positive perturbation, box or
  ///         success distance that is negative or not finite.
  explicit ReachTask(const ReachOptions& options = {});

  std::unique_ptr<EnvTask> clone() const override;
  std::string_view name() const noexcept override { return "reach"; }
  std::string_view description() const noexcept override;
  const Robot& robot() const noexcept override { return robot_; }
  const Chain& chain() const noexcept override { return *chain_; }
  std::vector<ArraySpec> observation_specs() const override;
  std::vector<std::string> default_observations() const override;

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override;
  void observe(int index, const StepContext& context,
               std::span<double> out) const noexcept override;
  double reward(const StepContext& context) const noexcept override;
  bool terminated(const StepContext& context) const noexcept override;

  const ReachOptions& options() const noexcept { return options_; }
  /// The target of the current episode (world, m).
  const Eigen::Vector3d& target() const noexcept { return target_; }

 private:
  ReachOptions options_;
  Robot robot_;
  std::optional<Chain> chain_;
  std::vector<double> qpos_start_;   // the keyframe's qpos
  std::vector<double> qpos_, qvel_;  // the episode's start (scratch)
  Eigen::Vector3d target_ = Eigen::Vector3d::Zero();
};

}  // namespace mjarm
