#pragma once
/// @file
/// `GraspMonitor`: how hard two fingers squeeze an object (from the contact forces, world axes)
/// and whether the object slips out of them (from its motion relative to the gripper).

#include <Eigen/Core>
#include <string_view>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/sim/contact_query.hpp"

namespace mjarm {

class Simulation;

/// Thresholds of a `GraspMonitor`.
struct GraspMonitorOptions {
  /// The object has slipped once it moved this far from its grasped pose relative to the
  /// gripper [m] (> 0): the event a task logs.
  double slip_distance = 0.002;
  /// ... and is lost (dropped) beyond this [m] (> slip_distance).
  double drop_distance = 0.015;
};

constexpr auto declared_fields(const GraspMonitorOptions*) {
  using S = GraspMonitorOptions;
  return declare<S>("grasp monitor",
                    field("slip_distance", &S::slip_distance, "m", Range::positive(),
                          "slip relative to the gripper that counts as slipped"),
                    field("drop_distance", &S::drop_distance, "m", Range::positive(),
                          "slip that counts as dropped; larger than slip_distance"));
}

/// What happened at one `GraspMonitor::update`.
enum class GraspEvent {
  none,     ///< nothing new
  slipped,  ///< the object moved more than slip_distance relative to the gripper (first time)
  dropped   ///< ... more than drop_distance (first time): the grasp is lost
};

constexpr auto declared_names(const GraspEvent*) {
  using E = GraspEvent;
  return std::array{EnumName{E::none, "none", "nothing new"},
                    EnumName{E::slipped, "slipped", "moved more than slip_distance (first time)"},
                    EnumName{E::dropped, "dropped", "moved more than drop_distance (first time)"}};
}

/// The grasp as the last `update` saw it.
struct GraspReading {
  int finger1_contacts = 0;  ///< contacts between finger 1's geoms and the object's
  int finger2_contacts = 0;
  /// Force each finger exerts on the object, summed over its contacts, world axes [N] (the
  /// contacts and constraint forces of the last completed physics step).
  Eigen::Vector3d force1_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d force2_W = Eigen::Vector3d::Zero();
  /// Grasp force ½‖f₁ − f₂‖ [N]: the squeeze. Two fingers pressing with F from opposite sides
  /// while carrying a load w give f₁ = F·n + w₁, f₂ = −F·n + w₂ with w₁ ≈ w₂, so this is F
  /// (the load shared evenly cancels).
  double force = 0.0;
  /// Net force of the fingers on the object f₁ + f₂, world axes [N]: the load carried (weight
  /// and inertia of a held object).
  Eigen::Vector3d load_W = Eigen::Vector3d::Zero();
  /// Distance the object's origin moved relative to the gripper frame since `close` [m] (0
  /// while not closed).
  double slip = 0.0;
  /// Speed of the object's origin relative to the gripper frame [m/s] (0 while not closed).
  double slip_speed = 0.0;
  bool closed = false;   ///< between `close` and `open`
  bool slipped = false;  ///< slip passed slip_distance since `close`
  bool dropped = false;  ///< slip passed drop_distance since `close`
};

/// Watches a two-finger grasp on one `Simulation`. `update` reads the contact summaries the
/// simulation refreshes after every tick and the state's kinematics and velocities (fresh inside
/// a control tick, e.g. from a task's `update`). Allocation-free after construction.
class GraspMonitor {
 public:
  /// @param gripper body carrying the fingers (its frame is the reference of the slip)
  /// @param object the grasped body
  /// @param finger1, finger2 geoms of each finger
  /// @throws Error for unknown bodies (closest names listed), empty finger sets or bad options.
  GraspMonitor(Simulation& simulation, std::string_view gripper, std::string_view object,
               const GeomSet& finger1, const GeomSet& finger2,
               const GraspMonitorOptions& options = {});

  /// Reads the grasp now; returns the event that happened at this update, if any.
  GraspEvent update() noexcept;
  /// The grasp is made: the object's current pose relative to the gripper becomes the grasped
  /// pose that slip is measured from; slipped/dropped are cleared.
  void close() noexcept;
  /// The grasp is let go: slip is no longer measured.
  void open() noexcept;

  const GraspReading& reading() const noexcept { return reading_; }
  const GraspMonitorOptions& options() const noexcept { return options_; }
  /// Where the reading's grasp force and slip live (for `RecorderOptions::channels`).
  const double* force_value() const noexcept { return &reading_.force; }
  const double* slip_value() const noexcept { return &reading_.slip; }
  int gripper() const noexcept { return gripper_; }
  int object() const noexcept { return object_; }

 private:
  const Simulation* simulation_;
  GraspMonitorOptions options_;
  int gripper_ = -1;
  int object_ = -1;
  int watch1_ = -1;
  int watch2_ = -1;
  Eigen::Vector3d p_GO_ = Eigen::Vector3d::Zero();  // grasped position of the object in G [m]
  GraspReading reading_;
};

}  // namespace mjarm
