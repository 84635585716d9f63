#pragma once
/// @file
/// `PythonEnvTask`: an `EnvTask` whose hooks are the methods of a Python object (a subclass of
/// `mjarm.EnvTask`, python/mjarm/env_task.py), run by the C++ environment like any task. Each
/// hook takes the GIL for its call only; what the task says once (robot, chain, name, specs) is
/// read at construction.
///
/// The hooks are noexcept: an exception raised by a Python method is kept in the task (the
/// first one of a step), the episode ends there (`terminated` is true, the reward NaN, the
/// mapped action zero) and the binding of `reset`/`step` raises it with its traceback; `reset`
/// starts a clean episode.
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "data_handle.hpp"
#include "mjarm/env/env_task.hpp"

namespace mjarm::python {

/// What a Python hook sees of the environment, valid for the call (its `data` refuses use after
/// it): the end-effector pose and twist, the step and the episode's time.
struct PyStepContext {
  Pose X_WE;
  Vector6d V_WE = Vector6d::Zero();
  int step = 0;
  double time = 0.0;
  py::object data;  ///< a call's `Data` of the simulation (invalidated after the call)
};

class PythonEnvTask final : public EnvTask {
 public:
  /// Reads what @p task says once. @throws what its methods raise, Error for a bad spec.
  explicit PythonEnvTask(py::object task);
  ~PythonEnvTask() override;
  PythonEnvTask(const PythonEnvTask&) = delete;
  PythonEnvTask& operator=(const PythonEnvTask&) = delete;

  /// The task's `clone()` (a shallow copy by default), for each environment of a batch.
  std::unique_ptr<EnvTask> clone() const override;
  std::string_view name() const noexcept override { return name_; }
  std::string_view description() const noexcept override { return description_; }
  const Robot& robot() const noexcept override { return robot_; }
  const Chain& chain() const noexcept override { return chain_; }

  std::vector<ArraySpec> observation_specs() const override { return observation_specs_; }
  std::vector<std::string> default_observations() const override;
  std::optional<ArraySpec> action_spec() const override { return action_spec_; }

  void initialize_episode(Simulation& sim, EpisodeRandom& random) override;
  void map_action(const StepContext& context, std::span<const double> action,
                  std::span<double> space_action) noexcept override;
  void before_step(const StepContext& context, std::span<const double> action) noexcept override;
  void after_step(const StepContext& context) noexcept override;
  void observe(int index, const StepContext& context,
               std::span<double> out) const noexcept override;
  double reward(const StepContext& context) const noexcept override;
  bool terminated(const StepContext& context) const noexcept override;

  /// The Python object.
  const py::object& object() const noexcept { return task_; }
  /// The exception a hook raised since the last call (null when none), taken.
  std::exception_ptr take_error() const noexcept { return std::exchange(error_, nullptr); }

 private:
  // runs @p call under the GIL with a context for Python; an exception is kept
  template <class F>
  void guarded(const StepContext* context, F&& call) const noexcept;

  py::object task_;
  std::string name_;
  std::string description_;
  Robot robot_;
  Chain chain_;
  std::optional<ArraySpec> action_spec_;
  std::vector<ArraySpec> observation_specs_;
  std::optional<std::vector<std::string>> default_observations_;
  mutable std::exception_ptr error_;
};

/// Raises the exception a Python task of @p task kept (nothing for a C++ task).
void raise_task_error(const EnvTask& task);

}  // namespace mjarm::python
