#pragma once
/// @file
/// `PickPlaceEnvTask`: the tasks room's pick and place as an environment task — the same scene
/// (a robot with a two-finger gripper on a table, a free cube, a target), the same draws of the
/// object and target for a seed and the same placement criteria, driven by an agent that moves
/// the tool and opens and closes the gripper.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/control/finger_force.hpp"
#include "mjarm/env/env_task.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/sim/grasp_monitor.hpp"
#include "mjarm/tasks/pick_place/pick_place.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"

namespace mjarm {

/// Settings of a `PickPlaceEnvTask`.
struct PickPlaceEnvOptions {
  std::string robot = "panda_hand";  ///< a robot of `pick_place_robots()` (its torque model)
  double object_half_size = 0.015;   ///< the cube's half extent [m] (> 0)
  double object_mass = 0.05;         ///< [kg] (> 0)
  double object_friction = 1.0;      ///< sliding friction of the cube (> 0)
  /// Where the cube and the target are drawn (`draw_pick_place_trial`: the robot's table region,
  /// the yaw range, the separation); the size, mass and friction ranges are not used (the cube
  /// is the one above; randomize it with `RandomizationOptions`).
  PickPlaceRanges ranges;
  /// Placement tolerance, rest speed and tilt of a placed cube; the grasp monitor's distances.
  PickPlaceCriteria criteria;
  double grasp_force = 8.0;  ///< the fingers' squeeze once touching [N] (> 0)
  /// Each arm joint of the home posture is perturbed uniformly within ± this [rad] (≥ 0).
  double start_perturbation = 0.02;
  /// A robot geom touching the table fails the episode (as it fails a trial of the tasks room).
  bool table_contact_fails = true;
  double failure_penalty = 1.0;  ///< subtracted from the reward of a failing step (≥ 0)
  int noslip_iterations = 10;    ///< MuJoCo's noslip iterations of the scene (as the trials)
};

/// `ranges` is checked where a trial is drawn.
constexpr auto declared_fields(const PickPlaceEnvOptions*) {
  using S = PickPlaceEnvOptions;
  return declare<S>(
      "pick-place environment", field("robot", &S::robot, "a robot of pick_place_robots()"),
      field("object_half_size", &S::object_half_size, "m", Range::positive(),
            "the cube's half extent"),
      field("object_mass", &S::object_mass, "kg", Range::positive(), "the cube's mass"),
      field("object_friction", &S::object_friction, "", Range::positive(),
            "sliding friction of the cube"),
      field("criteria", &S::criteria, "placement tolerance, rest speed and tilt of a placed cube"),
      field("grasp_force", &S::grasp_force, "N", Range::positive(),
            "the fingers' squeeze once touching"),
      field("start_perturbation", &S::start_perturbation, "rad", Range::non_negative(),
            "each arm joint of the home posture within ± this"),
      field("table_contact_fails", &S::table_contact_fails,
            "a robot geom touching the table fails the episode"),
      field("failure_penalty", &S::failure_penalty, "", Range::non_negative(),
            "subtracted from the reward of a failing step"),
      field("noslip_iterations", &S::noslip_iterations, "", Range::closed(0, 1000),
            "MuJoCo's noslip iterations of the scene"));
}

/// How a pick-and-place episode stands.
enum class PickPlaceEnvOutcome {
  running,        ///< not placed, not failed
  placed,         ///< the cube rests on the table at the target, upright, released: success
  fell,           ///< the cube left the table
  table_contact,  ///< a robot geom touched the table
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const PickPlaceEnvOutcome*) {
  using E = PickPlaceEnvOutcome;
  return std::array{EnumName{E::running, "running"}, EnumName{E::placed, "placed"},
                    EnumName{E::fell, "fell"}, EnumName{E::table_contact, "table_contact"}};
}

/// Pick and place: the arm starts at its `home` keyframe (each joint perturbed) with the
/// fingers open; for episode seed K the cube's position and yaw and the target are those of
/// `draw_pick_place_trial` with seed K (`mjarm run pick-place --robot ROBOT --seed K`). The
/// agent moves the tool (the action space's entries) and commands the gripper with one more
/// entry in [0, 1] (0 open, 1 closed): the tasks room's `FingerForceController` closes the
/// fingers until they squeeze with `grasp_force` once touching (a friction grasp — no weld).
/// The finger controller and the arm's run every physics step (`controller_period` 2 ms).
///
/// - Reward (dense): −(‖p_tool − p_cube‖ + ‖p_cube − p_target‖) [m] (p_target: the cube's
///   centre resting on the target); minus `failure_penalty` on a failing step.
/// - Terminates (discount 0) when placed — horizontal error ≤ placement_tolerance, the cube
///   within 5 mm of its resting height, speed ≤ rest_speed, tilt ≤ max_tilt, no finger touching
///   it — or on a failure: the cube below the table top, a robot geom on the table.
/// - Observations of its own: `object_pose` (7: the cube's position [m] and quaternion w x y z,
///   from the current qpos), `target` (3: where its centre should rest [m]), `target_offset`
///   (3: target − cube position [m]), `grasp` (4: finger opening [m] — the sum of the finger
///   joints —, finger 1 and finger 2 touching the cube (0/1), grasp force [N], `GraspMonitor`).
///   Defaults: joint_positions, joint_velocities, ee_pose, object_pose, target, grasp.
class PickPlaceEnvTask final : public EnvTask {
 public:
  /// @throws Error for an unknown robot, a cube that is not positive, ranges the trial draw
  ///         refuses, criteria or forces that are not positive, a negative perturbation or
  ///         penalty.
  explicit PickPlaceEnvTask(const PickPlaceEnvOptions& options = {});
  PickPlaceEnvTask(const PickPlaceEnvTask& other);
  PickPlaceEnvTask& operator=(const PickPlaceEnvTask&) = delete;
  ~PickPlaceEnvTask() override;

  std::unique_ptr<EnvTask> clone() const override;
  std::string_view name() const noexcept override { return "pick-place"; }
  std::string_view description() const noexcept override;
  const Robot& robot() const noexcept override { return scene_->model; }
  const Chain& chain() const noexcept override { return arm_; }
  std::vector<ArraySpec> observation_specs() const override;
  std::vector<std::string> default_observations() const override;
  std::vector<int> object_geoms() const override;
  bool gripper_action() const noexcept override { return true; }
  Controller* auxiliary_controller() noexcept override { return fingers_.get(); }
  double controller_period() const noexcept override;

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override;
  void after_step(const StepContext& context) noexcept override;
  void observe(int index, const StepContext& context,
               std::span<double> out) const noexcept override;
  double reward(const StepContext& context) const noexcept override;
  bool terminated(const StepContext& context) const noexcept override;

  const PickPlaceEnvOptions& options() const noexcept { return options_; }
  const PickPlaceScene& scene() const noexcept { return *scene_; }
  /// The draw of the current episode (cube position and yaw, target).
  const PickPlaceTrial& trial() const noexcept { return trial_; }
  /// Where the cube's centre should rest (world) [m].
  const Eigen::Vector3d& target() const noexcept { return target_; }
  /// The cube's pose after the last step (or at the start).
  const Pose& object_pose() const noexcept { return X_WO_; }
  /// The grasp monitor's last reading (null before the first episode).
  const GraspReading* grasp() const noexcept { return monitor_ ? &monitor_->reading() : nullptr; }
  PickPlaceEnvOutcome outcome() const noexcept { return outcome_; }

 private:
  void read_object(const mjData& d) noexcept;

  PickPlaceEnvOptions options_;
  std::shared_ptr<const PickPlaceScene> scene_;
  Chain arm_;
  std::unique_ptr<FingerForceController> fingers_;
  std::optional<GraspMonitor> monitor_;  // on the simulation of the first episode
  const Simulation* monitored_ = nullptr;
  int table_watch_ = -1;
  int object_body_ = -1, object_qpos_ = -1, object_dof_ = -1;
  std::array<int, 2> finger_qpos_{-1, -1};
  std::vector<double> home_, qpos_, qvel_;
  PickPlaceTrial trial_;
  double half_height_ = 0.0;
  Eigen::Vector3d target_ = Eigen::Vector3d::Zero();
  Pose X_WO_;
  Eigen::Vector4d object_quaternion_ = Eigen::Vector4d(1.0, 0.0, 0.0, 0.0);
  double object_speed_ = 0.0;
  PickPlaceEnvOutcome outcome_ = PickPlaceEnvOutcome::running;
};

}  // namespace mjarm
