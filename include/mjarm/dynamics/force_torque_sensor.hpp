#pragma once
/// @file
/// `ForceTorqueSensor`: reads an MJCF force/torque sensor pair at a site, expresses the wrench
/// in site, world or end-effector axes about a chosen point, and says when it was measured.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// When the `mjData` handed to `read` last computed its acceleration-stage sensors.
enum class SensorTiming {
  /// After `mj_step` or the split `mj_step1` (what `Simulation` runs before its controllers with
  /// the Euler integrator): sensordata of force/torque sensors was computed by the forward pass
  /// of the previous step, at d.time − timestep — one physics step old.
  after_step,
  /// After `mj_forward` on the current state (Simulation with RK4 runs one before its
  /// controllers): measured at d.time.
  after_forward
};

constexpr auto declared_names(const SensorTiming*) {
  return std::array{
      EnumName{SensorTiming::after_step, "after_step", "sensordata one physics step old"},
      EnumName{SensorTiming::after_forward, "after_forward", "measured at d.time"}};
}

/// Outcome of one read.
enum class WrenchStatus {
  ok,         ///< all six values finite
  non_finite  ///< a NaN or an infinity in sensordata: the wrench is set to zero, never used
};

constexpr auto declared_names(const WrenchStatus*) {
  return std::array{EnumName{WrenchStatus::ok, "ok", "all six values finite"},
                    EnumName{WrenchStatus::non_finite, "non_finite", "the wrench was zeroed"}};
}

/// One wrench measurement.
struct WrenchReading {
  /// [f; τ] (N; N·m), linear first, in the axes and about the point the read asked for. Sign
  /// (MuJoCo's force/torque sensors): the wrench the parent side of the sensor exerts on the
  /// sensor body and everything below it (the tool). A tool at rest with nothing touching it
  /// reads its own weight held up, f = −m_tool·gravity; a contact pushing the tool with F_env
  /// shows as −F_env.
  Vector6d wrench = Vector6d::Zero();
  /// Simulation time at which the value was measured [s] (d.time − age).
  double time = 0.0;
  /// d.time − time [s]: one physics timestep for `SensorTiming::after_step`, 0 otherwise.
  double age = 0.0;
  WrenchStatus status = WrenchStatus::ok;  ///< ok, or non_finite (wrench zeroed)
  bool ok() const noexcept { return status == WrenchStatus::ok; }
};

/// τ_B = τ_A + (p_A − p_B) × f: moves the moment point of a wrench [f; τ] from p_A to p_B
/// (all vectors in the same axes). The force is unchanged.
Vector6d shift_wrench(const Vector6d& F, const Eigen::Vector3d& p_A,
                      const Eigen::Vector3d& p_B) noexcept;

/// A `force` + `torque` sensor pair on one site S. MuJoCo's mjSENS_FORCE and mjSENS_TORQUE: the
/// interaction force and torque between the site's body and its parent body, expressed in S's
/// axes, the torque about S's origin; sensor noise and cutoff as the model sets them.
/// Reads allocate nothing and never throw.
class ForceTorqueSensor {
 public:
  /// Finds the sensor pair on site @p site of @p robot's model.
  /// @throws Error naming the site when it does not exist (with the closest site names), or
  ///         when it has no force or no torque sensor ("site 'flange' of model 'iiwa14' has no
  ///         force sensor; add <force site="flange"/> to <sensor>").
  ForceTorqueSensor(const Robot& robot, std::string_view site,
                    SensorTiming timing = SensorTiming::after_step);

  const std::string& site() const noexcept { return site_; }  ///< the site's name
  int site_id() const noexcept { return site_id_; }           ///< its id
  SensorTiming timing() const noexcept { return timing_; }    ///< as constructed
  const mjModel& model() const noexcept { return *model_; }    ///< the robot's model

  /// Wrench in S's axes about S's origin (the raw sensordata).
  WrenchReading read_site(const mjData& d) const noexcept;

  /// Wrench in world axes, moment about the world point @p p_WP (e.g. the end effector's origin
  /// p_WE: τ_P = R_WS·τ_S + (p_WS − p_WP) × f_W). S's pose is read from @p d.
  WrenchReading read_world(const mjData& d, const Eigen::Vector3d& p_WP) const noexcept;

  /// Wrench in E's axes about E's origin, for a frame E at pose @p X_WE (e.g.
  /// `ChainDynamics::pose()`): R_WEᵀ applied to `read_world(d, X_WE.p)`.
  WrenchReading read_body(const mjData& d, const Pose& X_WE) const noexcept;

 private:
  const mjModel* model_ = nullptr;
  std::string site_;
  int site_id_ = -1;
  int force_adr_ = -1;   // into sensordata
  int torque_adr_ = -1;  // into sensordata
  SensorTiming timing_ = SensorTiming::after_step;
};

}  // namespace mjarm
