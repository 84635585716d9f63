#pragma once
/// @file
/// `ObservationSet`: the observations an environment was asked for, by name, checked against
/// what the task, the model and the simulation can give, and written into one buffer.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mjarm/env/array_spec.hpp"
#include "mjarm/env/env_task.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {

/// The observations of an environment. Names (n = the chain's joints):
///
/// | name | shape | what |
/// |---|---|---|
/// | `joint_positions` | n | chain joint positions [rad or m], bounded by the joint limits |
/// | `joint_velocities` | n | chain joint velocities [rad/s or m/s] |
/// | `ee_pose` | 7 | end-effector position [m] and orientation quaternion (w, x, y, z), world |
/// | `ee_twist` | 6 | end-effector twist [v; ω] (m/s, rad/s), world axes |
/// | `contact_forces` | 3 | total contact force the rest of the scene exerts on the arm (every body
/// of the chain's root subtree: arm and tool), world axes [N] | | `sensor:NAME` | its dimension |
/// the MJCF sensor NAME (bounded by its cutoff when it has one) | | task names | task's | what the
/// task provides (`target`, `object_pose`, …) |
/// | `pixels:CAMERA` | h × w × 3 | the picture of model camera CAMERA (or `free`: a free camera
/// framing the model), RGB values 0…255, row 0 the top, rendered headless (EGL) |
/// | `depth:CAMERA` | h × w | its depth: distance from the camera's plane [m] |
///
/// Positions, velocities, pose and twist are computed from the current qpos and qvel; contact
/// forces and sensors are MuJoCo's, from the start of the step's last physics step (as
/// `Simulation::sensor`).
class ObservationSet {
 public:
  /// @param sim the environment's simulation (a contact watch is added for `contact_forces`)
  /// @throws Error for an unknown name (with the closest and every available name), a name
  ///         listed twice, a task observation this task does not provide (`target`,
  ///         `object_pose`: switched off here), a sensor the model does not have, or
  ///         `contact_forces` on a model whose contacts are disabled or whose arm has no
  ///         colliding geom. An empty list is an error too.
  /// @param pixels_width, pixels_height size of the `pixels:` and `depth:` images [pixels]
  ObservationSet(const EnvTask& task, Simulation& sim, const std::vector<std::string>& names,
                 int pixels_width = 84, int pixels_height = 84);
  ~ObservationSet();
  ObservationSet(const ObservationSet&) = delete;
  ObservationSet& operator=(const ObservationSet&) = delete;

  const ObservationSpec& spec() const noexcept { return spec_; }

  /// Writes every observation into @p out (spec().size() values). Allocation-free.
  void fill(const StepContext& context, const EnvTask& task, std::span<double> out) const noexcept;

  /// Every name @p task can give on its model: the built-in ones, the task's, one
  /// `sensor:NAME` per named sensor.
  static std::vector<std::string> available(const EnvTask& task);
  /// Names the environment knows as task observations, which a task may or may not provide.
  static const std::vector<std::string>& task_names();

 private:
  enum class Source {
    joint_positions,
    joint_velocities,
    ee_pose,
    ee_twist,
    contact_forces,
    sensor,
    task,
    pixels,
    depth
  };
  struct Entry {
    Source source = Source::joint_positions;
    int index = -1;  // sensor id, task observation index, contact watch handle or camera
  };
  struct Cameras;  // the renderer and the cameras of pixels and depth (observation_pixels.cpp)

  std::vector<Entry> entries_;
  ObservationSpec spec_;
  std::unique_ptr<Cameras> cameras_;
};

}  // namespace mjarm
