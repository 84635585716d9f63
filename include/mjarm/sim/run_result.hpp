#pragma once
/// @file
/// What one control tick and one run of a `Simulation` report, and the source of references
/// a run consumes.

#include <mujoco/mujoco.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "mjarm/control/reference.hpp"
#include "mjarm/fields.hpp"
#include "mjarm/sim/step_fault.hpp"

namespace mjarm {

/// Outcome of one control tick.
enum class TickStatus {
  ok,           ///< the period was simulated
  finished,     ///< the reference source reported the task complete (nothing integrated)
  diverged,     ///< a physics step diverged; see `TickResult::fault`
  bad_command,  ///< a controller wrote NaN/inf; see `TickResult::fault` (nothing integrated)
};

/// Outcome of `Simulation::run`.
enum class RunStatus {
  duration_reached,  ///< simulated the requested duration
  finished,          ///< the reference source reported the task complete
  diverged,          ///< stopped on a diverging step (state of the last good step kept)
  bad_command,       ///< stopped because a controller wrote NaN/inf
  interrupted        ///< stopped because SIGINT/SIGTERM arrived (see interrupt.hpp)
};

constexpr auto declared_names(const TickStatus*) {
  using S = TickStatus;
  return std::array{EnumName{S::ok, "ok", "the period was simulated"},
                    EnumName{S::finished, "finished", "the reference source reported the task complete"},
                    EnumName{S::diverged, "diverged", "a physics step diverged"},
                    EnumName{S::bad_command, "bad_command", "a controller wrote NaN/inf"}};
}

/// The run names are the recorder's status strings.
constexpr auto declared_names(const RunStatus*) {
  using S = RunStatus;
  return std::array{EnumName{S::duration_reached, "duration_reached", "simulated the requested duration"},
                    EnumName{S::finished, "finished", "the reference source reported the task complete"},
                    EnumName{S::diverged, "diverged", "stopped on a diverging step"},
                    EnumName{S::bad_command, "bad_command", "stopped because a controller wrote NaN/inf"},
                    EnumName{S::interrupted, "interrupted", "stopped because SIGINT/SIGTERM arrived"}};
}

/// One control tick. Plain data (no allocation).
struct TickResult {
  TickStatus status = TickStatus::ok;
  double time = 0.0;        ///< simulated time at the end of the tick [s]
  int saturated = 0;        ///< actuators clipped by this tick's commands
  StepFault fault;          ///< set when status is diverged or bad_command
  bool ok() const noexcept { return status == TickStatus::ok; }
};

/// One run.
struct RunResult {
  RunStatus status = RunStatus::duration_reached;
  double start_time = 0.0;         ///< [s]
  double end_time = 0.0;           ///< simulated time when the run stopped [s]
  std::int64_t ticks = 0;          ///< control ticks simulated
  std::int64_t physics_steps = 0;  ///< physics steps simulated
  StepFault fault;                 ///< the fault when diverged / bad_command
  std::string message;             ///< one line for people: what happened, when, where
  /// True when the run ended as asked (duration reached or task finished).
  bool ok() const noexcept {
    return status == RunStatus::duration_reached || status == RunStatus::finished;
  }
};

/// Produces the reference of each control tick; a task state machine implements it.
class ReferenceSource {
 public:
  virtual ~ReferenceSource() = default;

  /// Called once per control tick, before the controllers, with @p data holding fresh
  /// positions, velocities, kinematics (xpos, site poses), M, qfrc_bias and the contact list of
  /// the state at data.time. Constraint forces are not computed yet at this point: read contact
  /// forces through `Simulation::contacts` (last completed step).
  /// @param reference filled in place (keeps its previous contents)
  /// @return false when the task is complete: the run stops with `RunStatus::finished`.
  virtual bool update(const mjData& data, Reference& reference) noexcept = 0;
};

/// A `ReferenceSource` made of a callable `bool(const mjData&, Reference&)`.
class FunctionReferenceSource final : public ReferenceSource {
 public:
  using Function = std::function<bool(const mjData&, Reference&)>;
  explicit FunctionReferenceSource(Function f) : f_(std::move(f)) {}
  bool update(const mjData& data, Reference& reference) noexcept override {
    return f_(data, reference);
  }

 private:
  Function f_;
};

/// A `ReferenceSource` that always gives the same reference.
class ConstantReferenceSource final : public ReferenceSource {
 public:
  explicit ConstantReferenceSource(Reference reference) : reference_(std::move(reference)) {}
  bool update(const mjData&, Reference& reference) noexcept override {
    reference = reference_;  // same sizes each tick: Eigen reuses the storage
    return true;
  }

 private:
  Reference reference_;
};

}  // namespace mjarm
