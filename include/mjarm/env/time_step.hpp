#pragma once
/// @file
/// `TimeStep`: what an environment returns from `reset` and `step`, with dm_env's semantics —
/// the step type, the reward and discount (none on the first step) and the observation.

#include <optional>
#include <span>
#include <string_view>

#include "mjarm/env/array_spec.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

/// Where a time step stands in its episode (dm_env's `StepType`).
enum class StepType {
  first,  ///< returned by `reset`: no reward, no discount
  mid,    ///< an ordinary step
  last    ///< the episode ended: by termination (discount 0) or by the time limit (discount 1)
};

/// The names (`to_string`, JSON and CLI spelling; Python binds FIRST, MID, LAST as dm_env).
constexpr auto declared_names(const StepType*) {
  using E = StepType;
  return std::array{EnumName{E::first, "first"}, EnumName{E::mid, "mid"},
                    EnumName{E::last, "last"}};
}

/// Why an episode ended (an addition to dm_env, which tells only by the discount).
enum class EpisodeEnd {
  running,     ///< not ended
  terminated,  ///< the task ended it (success or failure): discount 0
  truncated,   ///< the time limit was reached: discount 1 (the state is not terminal)
  diverged     ///< the physics diverged (`Simulation` fault) and was stopped: discount 0
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const EpisodeEnd*) {
  using E = EpisodeEnd;
  return std::array{EnumName{E::running, "running", "not ended"},
                    EnumName{E::terminated, "terminated", "the task ended it: discount 0"},
                    EnumName{E::truncated, "truncated", "the time limit: discount 1"},
                    EnumName{E::diverged, "diverged", "the physics diverged: discount 0"}};
}

/// A read-only view of one observation: the arrays of an `ObservationSpec`, back to back.
/// It points into the environment's buffer and is valid until the next `step` or `reset`:
/// copy what must outlive that.
class Observation {
 public:
  Observation() = default;
  Observation(const ObservationSpec* spec, std::span<const double> values) noexcept
      : spec_(spec), values_(values) {}

  /// Every value, in spec order (spec().size() doubles).
  std::span<const double> values() const noexcept { return values_; }
  /// The array called @p name. @throws Error naming it and listing the arrays.
  std::span<const double> operator[](std::string_view name) const;
  /// Array @p i of the spec. @throws Error for an index out of range.
  std::span<const double> at(int i) const;
  const ObservationSpec& spec() const noexcept { return *spec_; }

 private:
  const ObservationSpec* spec_ = nullptr;
  std::span<const double> values_;
};

/// One step of an episode.
struct TimeStep {
  StepType step_type = StepType::first;
  std::optional<double> reward;    ///< none on FIRST
  std::optional<double> discount;  ///< none on FIRST; 0 on a termination, 1 otherwise
  Observation observation;
  EpisodeEnd end = EpisodeEnd::running;  ///< set on LAST

  bool first() const noexcept { return step_type == StepType::first; }
  bool mid() const noexcept { return step_type == StepType::mid; }
  bool last() const noexcept { return step_type == StepType::last; }
};

}  // namespace mjarm
