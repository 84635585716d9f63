#include "python_env_task.hpp"

#include <algorithm>
#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm::python {

namespace {

Chain chain_of(const py::object& task, const Robot& robot) {
  const py::object chain = task.attr("chain");
  if (py::isinstance<py::str>(chain)) return Chain(robot, chain.cast<std::string>());
  return chain.cast<Chain>();
}

std::string text_of(const py::object& task, const char* attribute) {
  return py::str(task.attr(attribute)).cast<std::string>();
}

// the values a Python hook returned, into @p out (its size)
void copy_values(const py::object& values, std::span<double> out, const char* what) {
  const Eigen::VectorXd v = to_vector(values, what, static_cast<Eigen::Index>(out.size()));
  std::copy_n(v.data(), out.size(), out.data());
}

}  // namespace

PythonEnvTask::PythonEnvTask(py::object task)
    : task_(std::move(task)),
      name_(text_of(task_, "name")),
      description_(text_of(task_, "description")),
      robot_(task_.attr("robot").cast<Robot>()),
      chain_(chain_of(task_, robot_)) {
  const py::object action = task_.attr("action_spec")();
  if (!action.is_none()) action_spec_ = action.cast<ArraySpec>();
  for (const py::handle spec : task_.attr("observation_specs")())
    observation_specs_.push_back(spec.cast<ArraySpec>());
  const py::object defaults = task_.attr("default_observations")();
  if (!defaults.is_none()) default_observations_ = defaults.cast<std::vector<std::string>>();
}

PythonEnvTask::~PythonEnvTask() {
  // the Python object goes with the GIL held, whichever thread drops the last environment
  py::gil_scoped_acquire gil;
  task_ = py::object();
}

std::unique_ptr<EnvTask> PythonEnvTask::clone() const {
  py::gil_scoped_acquire gil;
  return std::make_unique<PythonEnvTask>(task_.attr("clone")());
}

std::vector<std::string> PythonEnvTask::default_observations() const {
  return default_observations_ ? *default_observations_ : EnvTask::default_observations();
}

template <class F>
void PythonEnvTask::guarded(const StepContext* context, F&& call) const noexcept {
  py::gil_scoped_acquire gil;
  py::object data;
  try {
    py::object view = py::none();
    if (context != nullptr) {
      data = py::cast(DataHandle(robot_, const_cast<mjData*>(&context->data()), py::none()));
      view =
          py::cast(PyStepContext{context->X_WE, context->V_WE, context->step, context->time, data});
    }
    call(view);
  } catch (...) {
    if (!error_) error_ = std::current_exception();  // the first one is the cause
  }
  if (data) data.cast<DataHandle&>().valid = false;  // lent for this call only
}

void PythonEnvTask::initialize_episode(Simulation& sim, EpisodeRandom& random) {
  error_ = nullptr;  // a new episode starts clean
  py::gil_scoped_acquire gil;
  // the task's generator of this episode: NumPy's, seeded from the episode's seed
  const py::object numpy_random = py::module_::import("numpy.random");
  const py::object rng =
      numpy_random.attr("Generator")(numpy_random.attr("PCG64")(py::int_(random.seed)));
  try {
    task_.attr("initialize_episode")(py::cast(&sim, py::return_value_policy::reference), rng);
  } catch (...) {
    error_ = std::current_exception();
  }
}

void PythonEnvTask::map_action(const StepContext& context, std::span<const double> action,
                               std::span<double> space_action) noexcept {
  std::fill(space_action.begin(), space_action.end(), 0.0);
  guarded(&context, [&](const py::object& view) {
    const py::object mapped = task_.attr("map_action")(
        view, to_array(action.data(), static_cast<Eigen::Index>(action.size())));
    copy_values(mapped, space_action, "EnvTask.map_action result");
  });
}

void PythonEnvTask::before_step(const StepContext& context,
                                std::span<const double> action) noexcept {
  guarded(&context, [&](const py::object& view) {
    task_.attr("before_step")(view,
                              to_array(action.data(), static_cast<Eigen::Index>(action.size())));
  });
}

void PythonEnvTask::after_step(const StepContext& context) noexcept {
  guarded(&context, [&](const py::object& view) { task_.attr("after_step")(view); });
}

void PythonEnvTask::observe(int index, const StepContext& context,
                            std::span<double> out) const noexcept {
  std::fill(out.begin(), out.end(), 0.0);
  guarded(&context, [&](const py::object& view) {
    const std::string& name = observation_specs_[static_cast<std::size_t>(index)].name;
    copy_values(task_.attr("observe")(name, view), out, "EnvTask.observe result");
  });
}

double PythonEnvTask::reward(const StepContext& context) const noexcept {
  double r = std::numeric_limits<double>::quiet_NaN();
  guarded(&context, [&](const py::object& view) { r = task_.attr("reward")(view).cast<double>(); });
  return r;
}

bool PythonEnvTask::terminated(const StepContext& context) const noexcept {
  bool done = false;
  guarded(&context,
          [&](const py::object& view) { done = task_.attr("terminated")(view).cast<bool>(); });
  return done || error_ != nullptr;  // a hook that raised ends the episode
}

void raise_task_error(const EnvTask& task) {
  if (const auto* python = dynamic_cast<const PythonEnvTask*>(&task)) {
    if (std::exception_ptr e = python->take_error()) std::rethrow_exception(e);
  }
}

}  // namespace mjarm::python
