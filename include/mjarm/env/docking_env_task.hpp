#pragma once
/// @file
/// `DockingEnvTask`: the tasks room's peg-in-hole docking as an environment task — the same
/// scene (iiwa14, peg with a force/torque sensor, chamfered socket), start pose and seating
/// criteria, driven by an agent's actions instead of the scripted approach and insertion.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/env/env_task.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/tasks/docking/monitor.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/tasks/docking/task.hpp"

namespace mjarm {

/// Settings of a `DockingEnvTask`.
struct DockingEnvOptions {
  /// The scene (geometry, socket pose, F/T sensor, joint friction variant); the F/T sensor is
  /// required (it is among the default observations).
  DockingSceneOptions scene;
  /// The start: the tip `start_height` above the socket's top face, peg down (as
  /// `plan_docking`); the other motion values are not used.
  DockingMotion motion;
  /// Seating and failure thresholds: depth, lateral, tilt, tip speed (the seat), `max_force`
  /// (a contact force above it fails the episode). `window` is not used (see `seated_time`).
  DockingCriteria criteria;
  /// Each episode's believed socket — what the `target` observation shows — is the true one
  /// moved by an offset drawn uniformly within ±these (dx, dy [m]; dyaw [rad]): the error of the
  /// socket pose the robot believes in, as in `mjarm run docking --offset` (≥ 0 each).
  DockingOffset offset_range{0.001, 0.001, 0.0};
  /// Each arm joint of the start configuration is perturbed uniformly within ± this [rad] (≥ 0).
  double start_perturbation = 0.005;
  /// How long the seat must hold to terminate the episode (success) [s] (≥ 0; 0: one step).
  double seated_time = 0.2;
  /// Weight of the peg's tilt in the reward [m/rad] (≥ 0).
  double tilt_weight = 0.05;
  /// Subtracted from the reward of a step that fails the episode (≥ 0).
  double failure_penalty = 1.0;
};

/// The socket's pose (`scene.X_WS`), the signs of `offset_range` and the motion's standoff are
/// checked by hand.
constexpr auto declared_fields(const DockingEnvOptions*) {
  using S = DockingEnvOptions;
  return declare<S>("docking environment",
                    field("scene", &S::scene, "the peg, the socket, the sensor, joint friction"),
                    field("motion", &S::motion, "the start (start_height)"),
                    field("offset_range", &S::offset_range,
                          "each episode's believed socket off by up to ± these"),
                    field("criteria", &S::criteria, "seating and failure thresholds"),
                    field("start_perturbation", &S::start_perturbation, "rad",
                          Range::non_negative(), "each arm joint of the start within ± this"),
                    field("seated_time", &S::seated_time, "s", Range::non_negative(),
                          "how long the seat must hold; 0: one step"),
                    field("tilt_weight", &S::tilt_weight, "m/rad", Range::non_negative(),
                          "weight of the peg's tilt in the reward"),
                    field("failure_penalty", &S::failure_penalty, "", Range::non_negative(),
                          "subtracted from the reward of a failing step"));
}

/// Why a docking episode ended by the task's rule (or did not).
enum class DockingEnvOutcome {
  running,        ///< neither seated nor failed
  seated,         ///< every seating criterion held for `seated_time`: success
  excess_force,   ///< the socket pushed on the peg harder than `criteria.max_force`
  other_contact,  ///< a contact that is not peg–socket (arm on the socket, peg on the floor…)
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const DockingEnvOutcome*) {
  using E = DockingEnvOutcome;
  return std::array{EnumName{E::running, "running"}, EnumName{E::seated, "seated"},
                    EnumName{E::excess_force, "excess_force"},
                    EnumName{E::other_contact, "other_contact"}};
}

/// Docking: the iiwa14 starts with the peg above the socket (`plan_docking`'s start
/// configuration, each joint perturbed) and must seat the peg in the bore. Each step the
/// ground truth is probed as the docking run does (`DockingProbe`: the socket's wrench on the
/// peg, other contacts); the tip's depth below the top face, its distance to the bore axis and
/// the peg's tilt come from the tip pose after the step.
///
/// - Reward (dense): −(‖p_WE − p_seated‖ + w·tilt), the true seated tip position and the angle
///   between the peg's axis and the bore's; minus `failure_penalty` on a failing step.
/// - Terminates (discount 0) when seated — depth ≥ full depth − tolerance, lateral ≤
///   max_lateral, tilt ≤ max_tilt, tip speed ≤ max_speed, held for `seated_time` — or on a
///   failure: a contact force above `max_force`, or any contact other than peg–socket.
/// - Observations of its own: `target` (7: the believed seated tip pose, position [m] and
///   quaternion w x y z), `wrench` (6: the socket's wrench on the peg [f; τ], world axes, τ
///   about the tip [N, N·m] — ground truth), `insertion` (3: depth below the top face, lateral
///   distance to the bore axis [m], tilt [rad], of the true socket — privileged).
///   Defaults: joint_positions, joint_velocities, ee_pose, ee_twist, target and the F/T sensor
///   (`sensor:iiwa/peg/ft_force`, `sensor:iiwa/peg/ft_torque`).
class DockingEnvTask final : public EnvTask {
 public:
  /// @throws Error for bad scene, motion or criteria values (as the tasks room), a scene without
  ///         the F/T sensor, negative ranges, weights or times, or an unreachable start.
  explicit DockingEnvTask(const DockingEnvOptions& options = {});

  std::unique_ptr<EnvTask> clone() const override;
  std::string_view name() const noexcept override { return "docking"; }
  std::string_view description() const noexcept override;
  const Robot& robot() const noexcept override { return scene_->robot; }
  const Chain& chain() const noexcept override { return scene_->chain; }
  std::vector<ArraySpec> observation_specs() const override;
  std::vector<std::string> default_observations() const override;

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override;
  void after_step(const StepContext& context) noexcept override;
  void observe(int index, const StepContext& context,
               std::span<double> out) const noexcept override;
  double reward(const StepContext& context) const noexcept override;
  bool terminated(const StepContext& context) const noexcept override;

  const DockingEnvOptions& options() const noexcept { return options_; }
  const DockingScene& scene() const noexcept { return *scene_; }
  /// The true seated tip pose (world).
  const Pose& seated() const noexcept { return X_seated_; }
  /// The believed seated tip pose of the current episode (the `target` observation).
  const Pose& believed_seated() const noexcept { return X_believed_; }
  /// The offset of the current episode's believed socket.
  const DockingOffset& offset() const noexcept { return offset_; }
  /// The probe's sample of the last step (contacts, the socket's wrench on the peg).
  const DockingSample& sample() const noexcept { return sample_; }
  /// The tip's depth below the top face, lateral distance [m] and tilt [rad] after the last
  /// step (or at the start).
  const Eigen::Vector3d& insertion() const noexcept { return insertion_; }
  /// How the episode stands.
  DockingEnvOutcome outcome() const noexcept { return outcome_; }
  /// The start configuration before the perturbation (arm joints, rad).
  const Eigen::VectorXd& q_start() const noexcept { return q_start_; }

 private:
  void measure(const Pose& X_WE) noexcept;

  DockingEnvOptions options_;
  std::shared_ptr<const DockingScene> scene_;
  DockingProbe probe_;
  Pose X_seated_, X_believed_;
  Eigen::Vector4d believed_quaternion_ = Eigen::Vector4d::Zero();
  DockingOffset offset_;
  Eigen::VectorXd q_start_;
  std::vector<double> home_, qpos_, qvel_;
  double full_depth_ = 0.0;
  DockingSample sample_;
  Eigen::Vector3d insertion_ = Eigen::Vector3d::Zero();
  double seated_since_ = -1.0;  // episode time the seat began [s]; < 0: not seated
  DockingEnvOutcome outcome_ = DockingEnvOutcome::running;
};

}  // namespace mjarm
