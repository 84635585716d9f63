#pragma once
/// @file
/// `ShelfPickEnvTask`: the tasks room's shelf pick as an environment task — the same robot,
/// pick points, start and hold criterion, driven by an agent's actions instead of a scripted
/// approach.

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/env/env_task.hpp"
#include "mjarm/tasks/pick_monitor.hpp"
#include "mjarm/tasks/shelf_pick/plan.hpp"

namespace mjarm {

/// Settings of a `ShelfPickEnvTask`.
struct ShelfPickEnvOptions {
  std::string robot = "panda";  ///< a robot of `shelf_pick_robots()` with a pose task (panda)
  PickCriteria criteria;  ///< tolerance and hold time (1 mm, 200 ms, as `mjarm run shelf-pick`)
  /// Weight of the orientation error in the reward [m/rad] (≥ 0).
  double orientation_weight = 0.1;
};

/// The criteria are checked with their steady window against the hold time.
constexpr auto declared_fields(const ShelfPickEnvOptions*) {
  using S = ShelfPickEnvOptions;
  return declare<S>("shelf-pick environment",
                    field("robot", &S::robot, "a robot of shelf_pick_robots() with a pose task"),
                    field("criteria", &S::criteria, "tolerance and hold time"),
                    field("orientation_weight", &S::orientation_weight, "m/rad",
                          Range::non_negative(), "weight of the orientation error in the reward"));
}

/// Shelf pick: the tool starts at the `home` keyframe with every joint perturbed and must bring
/// its tip onto a pick point with the tool at its home orientation, then hold it there. For
/// episode seed K the start and the pick point are those of `mjarm run shelf-pick --robot
/// panda --seed K` (`draw_shelf_pick` on the task generator). A `PickMonitor` samples the tip
/// once per step; the episode terminates (discount 0) when the tip has stayed within the
/// tolerance for the hold time. Reward r = −(‖p_WE − p_pick‖ + w·‖log(R_WT·R_WEᵀ)‖) per step.
/// Observation of its own: `target` (7: pick point [m] and tool quaternion w, x, y, z).
class ShelfPickEnvTask final : public EnvTask {
 public:
  /// @throws Error for an unknown or position-only robot, criteria that are not positive, or a
  ///         negative orientation weight.
  explicit ShelfPickEnvTask(const ShelfPickEnvOptions& options = {});

  std::unique_ptr<EnvTask> clone() const override;
  std::string_view name() const noexcept override { return "shelf-pick"; }
  std::string_view description() const noexcept override;
  const Robot& robot() const noexcept override { return model_; }
  const Chain& chain() const noexcept override { return *chain_; }
  std::vector<ArraySpec> observation_specs() const override;

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override;
  void after_step(const StepContext& context) noexcept override;
  void observe(int index, const StepContext& context,
               std::span<double> out) const noexcept override;
  double reward(const StepContext& context) const noexcept override;
  bool terminated(const StepContext& context) const noexcept override;

  /// The pick pose of the current episode (world).
  const Pose& target() const noexcept { return X_WT_; }
  /// The hold monitor of the current episode.
  const PickMonitor& monitor() const noexcept { return monitor_; }
  /// The start configuration of the current episode (full qpos).
  const std::vector<double>& qpos_start() const noexcept { return qpos_; }

 private:
  ShelfPickEnvOptions options_;
  const ShelfPickRobot* robot_;
  Robot model_;
  std::optional<Chain> chain_;
  std::vector<double> home_;         // the home keyframe's qpos
  std::vector<double> qpos_, qvel_;  // the episode's start
  Pose X_WT_;                        // pick point, home tool orientation
  Eigen::Vector4d quaternion_;       // of X_WT_.R
  PickMonitor monitor_;
};

}  // namespace mjarm
