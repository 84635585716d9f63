#pragma once
/// @file
/// The wiping motion: the stroke to wipe and how well the robot knows the table (`WipingPath`),
/// its timing and force (`WipingMotion`), the explicit force loop (`WipingForceLoop`), the plan
/// (`plan_wiping`) and `WipingTask`, the reference source of approach, press, stroke and hold
/// (docs/scenarios.md).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <numbers>

#include "mjarm/control/reference.hpp"
#include "mjarm/control/wrench_source.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/random.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/tasks/tick_observer.hpp"
#include "mjarm/tasks/wiping/scene.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm {

class Recorder;

/// The straight stroke on the table, and how well the robot knows the table's height.
struct WipingPath {
  std::array<double, 2> center{0.55, 0.0};  ///< the stroke's midpoint on the table, x y [m]
  double heading = std::numbers::pi / 2;    ///< its direction, from +x about +z [rad]
  double length = 0.3;                      ///< [m]
  /// The robot believes the table's top is off by a height drawn uniformly from [−u, u] by the
  /// trial's seed [m]: the force loop, not the plan, finds the surface.
  double height_uncertainty = 0.003;
};

constexpr auto declared_fields(const WipingPath*) {
  using S = WipingPath;
  return declare<S>(
      "wiping path",
      field("center", &S::center, "m", Range::closed(-1.0, 1.0), "the stroke's midpoint, x y"),
      field("heading", &S::heading, "rad", Range::closed(-std::numbers::pi, std::numbers::pi),
            "the stroke's direction, from +x about +z"),
      field("length", &S::length, "m", Range::closed(0.01, 0.8), "the stroke's length"),
      field("height_uncertainty", &S::height_uncertainty, "m", Range::closed(0.0, 0.02),
            "believed table height off by U(−u, u), drawn from the seed"));
}

/// Timing, speed and force of the motion.
struct WipingMotion {
  double start_height = 0.05;  ///< the tip above the believed table at the start [m]
  double approach_time = 1.0;  ///< start → the stroke's start on the believed table [s]
  double force = 10.0;         ///< normal force to wipe with [N]
  double force_ramp = 0.3;     ///< linear ramp of the force after the approach [s]
  double settle_time = 0.3;    ///< at full force before the stroke [s]
  double speed = 0.05;         ///< cruise speed of the stroke [m/s]
  double acceleration = 0.5;   ///< its acceleration [m/s²]
  double hold_time = 0.2;      ///< at the stroke's end, still pressing [s]
};

constexpr auto declared_fields(const WipingMotion*) {
  using S = WipingMotion;
  return declare<S>(
      "wiping motion",
      field("start_height", &S::start_height, "m", Range::closed(0.005, 0.3),
            "the tip above the believed table at the start"),
      field("approach_time", &S::approach_time, "s", Range::closed(0.1, 10.0),
            "start → the stroke's start"),
      field("force", &S::force, "N", Range::closed(0.5, 60.0), "normal force to wipe with"),
      field("force_ramp", &S::force_ramp, "s", Range::closed(0.01, 5.0),
            "linear ramp of the force"),
      field("settle_time", &S::settle_time, "s", Range::closed(0.0, 5.0),
            "at full force before the stroke"),
      field("speed", &S::speed, "m/s", Range::closed(0.005, 0.5), "cruise speed of the stroke"),
      field("acceleration", &S::acceleration, "m/s²", Range::closed(0.01, 5.0),
            "acceleration of the stroke"),
      field("hold_time", &S::hold_time, "s", Range::closed(0.0, 5.0),
            "at the stroke's end, still pressing"));
}

/// The explicit force loop around the controller's force feed-forward: the normal force the
/// reference asks for is F_d + k_f·∫(F_d − F_m) dt, with F_m the F/T sensor's normal force (the
/// tool's weight taken out) plus the sensor's noise.
struct WipingForceLoop {
  double gain = 10.0;         ///< k_f [1/s] (0: feed-forward only)
  double sensor_noise = 0.2;  ///< σ of the noise on F_m, drawn from the seed [N]
};

constexpr auto declared_fields(const WipingForceLoop*) {
  using S = WipingForceLoop;
  return declare<S>("wiping force loop",
                    field("gain", &S::gain, "1/s", Range::closed(0.0, 200.0),
                          "k_f of the force integral; 0: feed-forward only"),
                    field("sensor_noise", &S::sensor_noise, "N", Range::closed(0.0, 10.0),
                          "σ of the noise on the sensor's normal force"));
}

/// Phases, in order; each change is written to the recorder as a "phase" event.
enum class WipingPhase {
  approach,  ///< down to the stroke's start on the believed table
  press,     ///< the force ramps in, then settles
  stroke,    ///< along the line at the set speed
  hold       ///< at the end, still pressing
};

constexpr auto declared_names(const WipingPhase*) {
  using E = WipingPhase;
  return std::array{EnumName{E::approach, "approach"}, EnumName{E::press, "press"},
                    EnumName{E::stroke, "stroke"}, EnumName{E::hold, "hold"}};
}

/// Everything fixed before the run.
struct WipingPlan {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();       ///< the stroke's start (tip) [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< unit, horizontal
  double length = 0.0;                                   ///< [m]
  double true_height = 0.0;                              ///< the table's top [m]
  double believed_height = 0.0;                          ///< what the plan takes it for [m]
  Pose X_start;                                          ///< the tip at the start, pointing down
  Eigen::VectorXd q_start;     ///< the arm there (IK from the home keyframe) [rad]
  double approach_time = 0.0;  ///< [s]
  double press_time = 0.0;     ///< ramp + settle [s]
  double stroke_time = 0.0;    ///< [s]
  double hold_time = 0.0;      ///< [s]
  double duration() const noexcept { return approach_time + press_time + stroke_time + hold_time; }
  /// When the stroke begins, from the start [s].
  double stroke_start() const noexcept { return approach_time + press_time; }
};

/// The plan of a wiping run: the believed table height (drawn from @p seed), the stroke, the
/// start configuration by IK (from the home keyframe, pulled towards it), phase durations.
/// @throws Error for a value out of range, a stroke that leaves the table (with the pad's
///         radius to spare), or a start the arm cannot reach
WipingPlan plan_wiping(const WipingScene& scene, const WipingPath& path, const WipingMotion& motion,
                       std::uint64_t seed);

/// The wiping reference, one control tick at a time, from t₀ (data.time at the first update):
/// approach (SE(3) interpolation, rest to rest), press (the force ramps in), stroke (trapezoid in
/// speed along the line), hold; the tool points straight down throughout. reference.task.F_ext
/// is the force the tool should exert on the table: (0, 0, −F), F = F_d + k_f·∫(F_d − F_m) dt
/// from the press on, the integral bounded so that 0 ≤ F ≤ 2·F_d. reference.joint.q is q_start
/// (the null-space posture). `update` returns false at t₀ + duration; it allocates nothing and
/// never throws.
class WipingTask final : public ReferenceSource {
 public:
  /// @param scene the scene the run simulates (must outlive the task: the task reads its F/T
  ///        sensor)
  /// @param recorder where phase events go (may be null; must outlive the task)
  /// @throws Error for a force loop out of range
  WipingTask(const WipingScene& scene, const WipingPlan& plan, const WipingMotion& motion,
             const WipingForceLoop& loop, std::uint64_t seed, Recorder* recorder = nullptr);

  bool update(const mjData& data, Reference& reference) noexcept override;

  WipingPhase phase() const noexcept { return phase_; }
  /// The tip's reference position of the last update [m].
  const Eigen::Vector3d& reference_position() const noexcept { return p_WD_; }
  /// The normal force of the last update: asked for (F_d, ramped) and sent (F) [N].
  double desired_force() const noexcept { return desired_force_; }
  double commanded_force() const noexcept { return commanded_force_; }
  /// Simulated time of the first update (NaN before).
  double start_time() const noexcept { return t0_; }
  /// Calls @p observer at every update (a video); may be null.
  void set_observer(TickObserver* observer) noexcept { observer_ = observer; }

 private:
  void enter(WipingPhase phase, double time) noexcept;

  const WipingScene& scene_;
  WipingPlan plan_;
  WipingMotion motion_;
  WipingForceLoop loop_;
  Recorder* recorder_;
  TickObserver* observer_ = nullptr;
  WrenchSource sensor_;
  Random noise_;
  Se3Interpolation approach_;
  TrapezoidProfile stroke_;
  WipingPhase phase_ = WipingPhase::approach;
  bool started_ = false;
  double t0_;
  double last_time_ = 0.0;
  double integral_ = 0.0;  // ∫(F_d − F_m) dt [N·s]
  Eigen::Vector3d p_WD_ = Eigen::Vector3d::Zero();
  double desired_force_ = 0.0;
  double commanded_force_ = 0.0;
};

}  // namespace mjarm
