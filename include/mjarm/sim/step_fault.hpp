#pragma once
/// @file
/// Divergence detection: what stops a simulation, where and when.

#include <mujoco/mujoco.h>

#include <array>
#include <string>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Why a simulation stopped stepping.
enum class FaultCause {
  none,                ///< no fault
  mujoco_warning,      ///< MuJoCo flagged bad qpos/qvel/qacc/ctrl or a singular inertia
  nonfinite_qpos,      ///< NaN/inf in qpos after a step
  nonfinite_qvel,      ///< NaN/inf in qvel after a step
  nonfinite_qacc,      ///< NaN/inf in qacc
  acceleration_bound,  ///< |qacc| above `SimulationOptions::max_acceleration`
  bad_command          ///< a controller wrote NaN/inf (or a command of the wrong size/kind)
};

constexpr auto declared_names(const FaultCause*) {
  using C = FaultCause;
  return std::array{EnumName{C::none, "none", "no fault"},
                    EnumName{C::mujoco_warning, "mujoco_warning", "MuJoCo flagged a fatal warning"},
                    EnumName{C::nonfinite_qpos, "nonfinite_qpos", "NaN/inf in qpos after a step"},
                    EnumName{C::nonfinite_qvel, "nonfinite_qvel", "NaN/inf in qvel after a step"},
                    EnumName{C::nonfinite_qacc, "nonfinite_qacc", "NaN/inf in qacc"},
                    EnumName{C::acceleration_bound, "acceleration_bound", "|qacc| above the bound"},
                    EnumName{C::bad_command, "bad_command", "a controller wrote NaN/inf"}};
}

/// A fault and where it happened. Plain data: filled in the step loop without allocating.
struct StepFault {
  FaultCause cause = FaultCause::none;
  double time = 0.0;    ///< simulated time at the start of the failing step [s]
  int joint = -1;       ///< joint id of the offending dof (−1 when not a joint)
  int dof = -1;         ///< index into qvel/qacc (or into qpos for qpos faults)
  int actuator = -1;    ///< actuator id for ctrl faults
  int warning = -1;     ///< mjtWarning for `mujoco_warning`
  int controller = -1;  ///< controller index for `bad_command`
  double value = 0.0;   ///< the offending value
  bool ok() const noexcept { return cause == FaultCause::none; }
};

/// Checks one `mjData` after each step. Fatal MuJoCo warnings (bad qpos/qvel/qacc/ctrl, singular
/// inertia) are read from d->warning: MuJoCo resets the data when it raises them, so they must be
/// caught right after the call that raised them.
class DivergenceDetector {
 public:
  /// @param max_acceleration bound on |qacc| [rad/s² or m/s²] (+inf: NaN/inf only)
  explicit DivergenceDetector(double max_acceleration) noexcept
      : max_acceleration_(max_acceleration) {}

  /// Takes the current warning counters as the baseline (call after a reset).
  void rebase(const mjData& d) noexcept;

  /// A fault when a fatal warning counter grew since the baseline; `time` is what the caller
  /// knows as the step's start time (MuJoCo's reset zeroes d->time).
  StepFault check_warnings(const mjModel& m, const mjData& d, double time) noexcept;

  /// A fault when qpos/qvel/qacc hold NaN/inf or |qacc| exceeds the bound (after mj_step2).
  StepFault check_state(const mjModel& m, const mjData& d, double time) const noexcept;

  /// Warnings that are not fatal (contact/constraint buffers full) and grew since the baseline
  /// for the first time: returns the mjtWarning, or −1. Each kind is reported once per baseline.
  int new_benign_warning(const mjData& d) noexcept;

  double max_acceleration() const noexcept { return max_acceleration_; }

 private:
  double max_acceleration_;
  std::array<int, mjNWARNING> baseline_{};
  std::array<bool, mjNWARNING> reported_{};
};

/// The joint owning qpos index @p qpos_index, or −1.
int joint_of_qpos(const mjModel& m, int qpos_index) noexcept;

/// "t = 0.1240 s: NaN/inf in qacc at joint 'elbow' (dof 1, value nan)", for messages.
/// @param controller_name name of the controller for `bad_command` (may be empty)
std::string describe(const mjModel& m, const StepFault& fault, const std::string& controller_name = {});

}  // namespace mjarm
