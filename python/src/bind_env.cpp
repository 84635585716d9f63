// env room: Environment and VectorEnvironment with dm_env's interface (the time steps, specs
// and options are registered by bind_env_types.cpp). The Gymnasium-style adapters are pure
// Python on top of these (python/mjarm/gym.py).
//
// Lifetimes: the C++ observation is a view into the environment's buffer, valid until the next
// step. Python never sees that buffer: every TimeStep owns a copy of its observation (one
// array; the dict's entries are views of that copy), so a time step kept across steps never
// changes and never aliases the environment.
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "env_time_steps.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/env/observation_set.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/env/vector_environment.hpp"
#include "mjarm/scenarios/scenario.hpp"
#include "parameter_values.hpp"
#include "python_env_task.hpp"

namespace mjarm::python {
namespace {

/// Refuses a second thread into an environment stepping with the GIL released.
class Busy {
 public:
  Busy(bool& flag, const char* what) : flag_(flag) {
    if (flag_) {
      throw Error(std::string(what) +
                  ": already stepping in another thread (an environment is not thread-safe: "
                  "give each thread its own)");
    }
    flag_ = true;
  }
  ~Busy() { flag_ = false; }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  bool& flag_;
};

struct PyEnvironment {
  std::unique_ptr<Environment> env;
  std::shared_ptr<const ObservationLayout> layout;
  std::string task;
  std::vector<double> action;  // the action being stepped
  bool busy = false;

  PyTimeStep convert(const TimeStep& ts) const {
    PyTimeStep out;
    out.step_type = ts.step_type;
    out.reward = ts.reward;
    out.discount = ts.discount;
    out.end = ts.end;
    const auto values = ts.observation.values();
    out.copy.assign(values.begin(), values.end());
    out.layout = layout;
    return out;
  }
};

struct PyVectorEnvironment {
  std::unique_ptr<VectorEnvironment> env;
  std::shared_ptr<const ObservationLayout> layout;
  std::string task;
  std::vector<double> actions;  // row-major N × action size
  bool busy = false;

  PyVectorTimeStep convert() const {
    const VectorEnvironment& v = *env;
    const auto n = static_cast<py::ssize_t>(v.size());
    PyVectorTimeStep out;
    out.step_type = py::array_t<std::int8_t>(n);
    out.end = py::array_t<std::int8_t>(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      out.step_type.mutable_data()[i] = static_cast<std::int8_t>(v.step_types()[i]);
      out.end.mutable_data()[i] = static_cast<std::int8_t>(v.ends()[i]);
    }
    out.reward = to_array(v.rewards().data(), n);
    out.discount = to_array(v.discounts().data(), n);
    out.values = py::array_t<double>({n, layout->size});
    std::copy(v.observations().begin(), v.observations().end(), out.values.mutable_data());
    out.observation = layout->batch_dict_of(v.observations().data(), n);
    return out;
  }
};

/// Copies the action @p object into @p out (its size): a C-contiguous float64 array of that
/// shape directly, anything else through `to_vector` (conversion, the shape's ValueError).
void read_action(py::handle object, std::span<double> out) {
  if (py::isinstance<py::array_t<double, py::array::c_style>>(object)) {
    const auto a = py::reinterpret_borrow<py::array>(object);
    if (a.ndim() == 1 && a.shape(0) == static_cast<py::ssize_t>(out.size())) {
      std::copy_n(static_cast<const double*>(a.data()), out.size(), out.data());
      return;
    }
  }
  const Eigen::VectorXd v = to_vector(object, "action", static_cast<Eigen::Index>(out.size()));
  std::copy_n(v.data(), out.size(), out.data());
}

/// The scalar spec dm_env gives rewards and discounts.
ArraySpec scalar_spec(std::string name, double lo, double hi) {
  ArraySpec s;
  s.name = std::move(name);
  s.minimum = Eigen::VectorXd::Constant(1, lo);
  s.maximum = Eigen::VectorXd::Constant(1, hi);
  return s;
}

py::dict observation_specs(const ObservationSpec& spec) {
  py::dict out;
  for (const ArraySpec& a : spec.arrays()) out[py::str(a.name)] = a;
  return out;
}

/// An episode seed from Python: None, or an integer in [0, 2^64).
std::optional<std::uint64_t> to_seed(py::handle seed) {
  if (seed.is_none()) return std::nullopt;
  const auto refuse = [&] {
    return Error("reset: seed must be None or an integer in [0, 2^64), got " +
                 py::repr(seed).cast<std::string>());
  };
  // any integer (Python's, NumPy's: whatever has __index__), not a bool
  if (py::isinstance<py::bool_>(seed) || !py::hasattr(seed, "__index__")) throw refuse();
  const py::int_ i = seed.attr("__index__")();
  if (i < py::int_(0) || i >= py::int_(py::module_::import("builtins").attr("pow")(2, 64)))
    throw refuse();
  return i.cast<std::uint64_t>();
}

/// Options from an `EnvironmentOptions` (or None) with keyword overrides by field name.
EnvironmentOptions to_options(py::handle options, const py::kwargs& overrides) {
  py::object o = options.is_none() ? py::cast(EnvironmentOptions{})
                                   : py::cast(options.cast<EnvironmentOptions>());
  for (const auto& [key, value] : overrides) {
    const std::string name = py::str(key);
    if (name.empty() || name[0] == '_' || !py::hasattr(o, name.c_str())) {
      throw Error("environment: unknown option '" + name +
                  "' (see EnvironmentOptions: action_space, action, control_period, "
                  "controller_period, time_limit, observations, refuse_out_of_bounds, "
                  "randomization, seed, max_acceleration, observation_noise, action_latency)");
    }
    o.attr(name.c_str()) = value;
  }
  return o.cast<EnvironmentOptions>();
}

/// A task written in Python: an instance of `mjarm.EnvTask` (python/mjarm/env_task.py) run by
/// a `PythonEnvTask`; null for a task name.
std::unique_ptr<EnvTask> python_task(const py::object& task) {
  if (py::isinstance<py::str>(task)) return nullptr;
  const py::object base = py::module_::import("mjarm.env_task").attr("EnvTask");
  if (!py::isinstance(task, base)) {
    throw py::type_error(
        "environment: the task is a name (env_task_names()) or an instance of a "
        "subclass of mjarm.EnvTask, got " +
        py::str(py::type::of(task).attr("__name__")).cast<std::string>());
  }
  return std::make_unique<PythonEnvTask>(task);
}

/// Raises what a Python task's hook raised in environment @p i of @p v (the first one).
void raise_task_errors(const VectorEnvironment& v) {
  for (int i = 0; i < v.size(); ++i) raise_task_error(v.environment(i).task());
}

PyEnvironment make_environment(const py::object& task, py::handle options, py::handle task_options,
                               const py::kwargs& overrides) {
  const EnvironmentOptions o = to_options(options, overrides);
  std::unique_ptr<EnvTask> own = python_task(task);
  if (own && !task_options.is_none())
    throw Error(
        "environment: task_options are for a task by name; a Python task takes its "
        "options in its own constructor");
  const nlohmann::ordered_json values = task_options.is_none()
                                            ? nlohmann::ordered_json::object()
                                            : values_json(py::cast<py::dict>(task_options));
  PyEnvironment e;
  {
    py::gil_scoped_release release;
    e.env = std::make_unique<Environment>(
        own ? std::move(own) : make_env_task(task.cast<std::string>(), values), o);
  }
  e.layout = std::make_shared<const ObservationLayout>(e.env->observation_spec());
  e.task = std::string(e.env->task().name());
  e.action.resize(static_cast<std::size_t>(e.env->action_spec().size()));
  return e;
}

void bind_environment(py::module_& m) {
  py::class_<PyStepContext>(
      m, "StepContext",
      "What a Python task's hook sees of the environment (valid for the call): the chain's "
      "end-effector pose and twist after the physics, the step and the episode's time, and the "
      "simulation's state as a Data lent for the call.")
      .def_readonly("X_WE", &PyStepContext::X_WE, "end-effector pose in W")
      .def_property_readonly(
          "V_WE", [](const PyStepContext& c) { return Eigen::VectorXd(c.V_WE); },
          "end-effector twist (6,) [v; w], world axes [m/s, rad/s]")
      .def_readonly("step", &PyStepContext::step, "control steps since the episode's start")
      .def_readonly("time", &PyStepContext::time, "simulated time since the episode's start [s]")
      .def_readonly("data", &PyStepContext::data,
                    "the simulation's Data, lent for the call (read-only arrays)");

  py::class_<PyEnvironment>(
      m, "Environment",
      "A learning environment with dm_env's interface on a task (reach, shelf-pick): reset() -> "
      "FIRST, step(action) -> MID or LAST; a time-limit LAST has discount 1 (truncation), a "
      "termination or divergence discount 0. Actions outside their bounds are clipped and "
      "counted (or refused with refuse_out_of_bounds). The GIL is released while it steps. "
      "Not thread-safe: one thread per environment. See docs/env.md and docs/python.md.")
      .def(py::init(&make_environment), py::arg("task"), py::arg("options") = py::none(),
           py::arg("task_options") = py::none(),
           "Environment(task, options=None, task_options=None, **overrides): the task by name "
           "(env_task_names()) with its own options set from the dict task_options (names as "
           "env_task_parameters(task) lists them, e.g. {'criteria.max-force': 30}), or an "
           "instance of a subclass of mjarm.EnvTask (a task written in Python: its hooks run "
           "with the GIL taken for each call, and an exception a hook raises ends the episode "
           "and is raised by reset/step), with "
           "EnvironmentOptions (None: the defaults) whose fields keyword arguments override "
           "(e.g. time_limit=0.5, action_space='joint_torques'). Raises mjarm.Error for an "
           "unknown task, task option, observation or option, and options out of range.")
      .def(
          "reset",
          [](PyEnvironment& e, py::handle seed) {
            const auto s = to_seed(seed);
            Busy busy(e.busy, "Environment.reset");
            TimeStep ts;
            {
              py::gil_scoped_release release;
              ts = s ? e.env->reset(*s) : e.env->reset();
            }
            raise_task_error(e.env->task());
            return e.convert(ts);
          },
          py::arg("seed") = py::none(),
          "Starts an episode and returns its FIRST TimeStep. seed: an integer in [0, 2^64) (the "
          "same seed and actions give the same observations bit for bit), or None: the next "
          "seed of the environment's own sequence (EnvironmentOptions.seed).")
      .def(
          "step",
          [](PyEnvironment& e, py::handle action) {
            Busy busy(e.busy, "Environment.step");
            read_action(action, e.action);
            TimeStep ts;
            {
              py::gil_scoped_release release;
              ts = e.env->step(e.action);
            }
            raise_task_error(e.env->task());
            return e.convert(ts);
          },
          py::arg("action"),
          "One control step with action (float64 array-like of shape action_spec().shape) -> "
          "MID or LAST TimeStep. Raises ValueError naming the expected shape for a wrong "
          "shape or dtype, mjarm.Error for NaN/inf, before the first reset and after LAST "
          "(call reset()).")
      .def(
          "action_spec", [](const PyEnvironment& e) { return e.env->action_spec(); },
          "ArraySpec 'action': shape (n,), float64, its bounds.")
      .def(
          "observation_spec",
          [](const PyEnvironment& e) { return observation_specs(e.env->observation_spec()); },
          "dict name -> ArraySpec, in the order of the observation.")
      .def(
          "reward_spec",
          [](const PyEnvironment&) { return scalar_spec("reward", -INFINITY, INFINITY); },
          "ArraySpec 'reward': a float64 scalar, unbounded (dm_env's default).")
      .def(
          "discount_spec", [](const PyEnvironment&) { return scalar_spec("discount", 0.0, 1.0); },
          "ArraySpec 'discount': a float64 scalar in [0, 1] (dm_env's default).")
      .def(
          "close", [](PyEnvironment& e) { e.env->close(); },
          "Closes the environment (dm_env's interface): reset() and step() then raise "
          "mjarm.Error; a closed environment stays closed. Closing twice is allowed; the memory "
          "goes with the object.")
      .def_property_readonly(
          "closed", [](const PyEnvironment& e) { return e.env->closed(); }, "True after close()")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](PyEnvironment& e, py::args) {
            e.env->close();
            return false;
          },
          "Leaves a `with` block: close().")
      .def_readonly("task", &PyEnvironment::task, "the task's name")
      .def_property_readonly(
          "options", [](const PyEnvironment& e) { return e.env->options(); },
          "the EnvironmentOptions (a copy)")
      .def_property_readonly(
          "steps", [](const PyEnvironment& e) { return e.env->steps(); },
          "steps taken in the current episode")
      .def_property_readonly(
          "step_limit", [](const PyEnvironment& e) { return e.env->step_limit(); },
          "steps after which an episode is truncated: ceil(time_limit / T)")
      .def_property_readonly(
          "episode_seed", [](const PyEnvironment& e) { return e.env->episode_seed(); },
          "seed of the current episode")
      .def_property_readonly(
          "physics_steps_per_step",
          [](const PyEnvironment& e) { return e.env->physics_steps_per_step(); },
          "physics steps per control step (T / h)")
      .def_property_readonly(
          "episode_clips", [](const PyEnvironment& e) { return e.env->episode_clips(); },
          "ClipCounts of the current episode")
      .def_property_readonly(
          "total_clips", [](const PyEnvironment& e) { return e.env->total_clips(); },
          "ClipCounts since construction")
      .def_property_readonly(
          "end", [](const PyEnvironment& e) { return e.env->time_step().end; },
          "EpisodeEnd of the last time step (running until LAST)");

  py::class_<PyVectorEnvironment>(
      m, "VectorEnvironment",
      "N environments of one task stepped together on a thread pool (the GIL released), with "
      "automatic resets: a row whose last step was LAST is reset by the next step (its action "
      "row checked but unused) and returns FIRST. Environment i is seeded splitmix64(seed + i): "
      "the results are the same bit for bit whatever the thread count.")
      .def(py::init([](const py::object& task, int count, int threads, py::handle options,
                       const py::kwargs& overrides) {
             const EnvironmentOptions o = to_options(options, overrides);
             std::unique_ptr<EnvTask> own = python_task(task);
             PyVectorEnvironment v;
             {
               py::gil_scoped_release release;
               v.env = own ? std::make_unique<VectorEnvironment>(std::move(own), o, count, threads)
                           : std::make_unique<VectorEnvironment>(task.cast<std::string>(), o, count,
                                                                 threads);
             }
             v.layout = std::make_shared<const ObservationLayout>(v.env->observation_spec());
             v.task = std::string(v.env->environment(0).task().name());
             v.actions.resize(static_cast<std::size_t>(count) *
                              static_cast<std::size_t>(v.env->action_spec().size()));
             return v;
           }),
           py::arg("task"), py::arg("count"), py::arg("threads") = 1,
           py::arg("options") = py::none(),
           "VectorEnvironment(task, count, threads=1, options=None, **overrides): count "
           "environments (1..4096) on threads threads (1..256). Raises mjarm.Error as "
           "Environment, and for counts out of range.")
      .def(
          "reset",
          [](PyVectorEnvironment& v) {
            Busy busy(v.busy, "VectorEnvironment.reset");
            {
              py::gil_scoped_release release;
              v.env->reset();
            }
            raise_task_errors(*v.env);
            return v.convert();
          },
          "Resets every environment (the next seed of each one's sequence): every row FIRST.")
      .def(
          "step",
          [](PyVectorEnvironment& v, py::handle actions) {
            const int n = v.env->action_spec().size();
            const Eigen::MatrixXd a = to_matrix(actions, "actions", v.env->size(), n);
            for (Eigen::Index r = 0; r < a.rows(); ++r)
              for (Eigen::Index c = 0; c < a.cols(); ++c)
                v.actions[static_cast<std::size_t>(r * n + c)] = a(r, c);
            Busy busy(v.busy, "VectorEnvironment.step");
            {
              py::gil_scoped_release release;
              v.env->step(v.actions);
            }
            raise_task_errors(*v.env);
            return v.convert();
          },
          py::arg("actions"),
          "One step of every environment with actions (N, action size); rows whose last step "
          "was LAST are reset instead. Returns a VectorTimeStep. Raises ValueError naming the "
          "expected shape, mjarm.Error for NaN/inf (naming the row) or before reset(); nothing "
          "is stepped then.")
      .def(
          "close", [](PyVectorEnvironment& v) { v.env->close(); },
          "Closes every environment: reset() and step() then raise mjarm.Error; a closed "
          "environment stays closed. Closing twice is allowed.")
      .def_property_readonly(
          "closed", [](const PyVectorEnvironment& v) { return v.env->closed(); },
          "True after close()")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](PyVectorEnvironment& v, py::args) {
            v.env->close();
            return false;
          },
          "Leaves a `with` block: close().")
      .def_property_readonly(
          "size", [](const PyVectorEnvironment& v) { return v.env->size(); },
          "number of environments N")
      .def("__len__", [](const PyVectorEnvironment& v) { return v.env->size(); })
      .def_property_readonly(
          "threads", [](const PyVectorEnvironment& v) { return v.env->threads(); },
          "threads of the pool")
      .def_readonly("task", &PyVectorEnvironment::task, "the task's name")
      .def(
          "action_spec", [](const PyVectorEnvironment& v) { return v.env->action_spec(); },
          "ArraySpec of one environment's action (a batch is (N, *shape)).")
      .def(
          "observation_spec",
          [](const PyVectorEnvironment& v) { return observation_specs(v.env->observation_spec()); },
          "dict name -> ArraySpec of one environment's observation.")
      .def_property_readonly(
          "last_thread_cpu_seconds",
          [](const PyVectorEnvironment& v) { return v.env->last_thread_cpu_seconds(); },
          "CPU time [s] of each pool thread in the last reset or step")
      .def_property_readonly(
          "last_env_cpu_seconds",
          [](const PyVectorEnvironment& v) {
            const auto s = v.env->last_env_cpu_seconds();
            return to_array(s.data(), static_cast<Eigen::Index>(s.size()));
          },
          "(N,) CPU time [s] of each environment's part of the last reset or step")
      .def(
          "episode_clips",
          [](const PyVectorEnvironment& v, int i) { return v.env->environment(i).episode_clips(); },
          py::arg("i"), "ClipCounts of environment i's current episode.");

  m.def("env_task_names", &env_task_names, "The environment tasks' names ('reach', ...).");
  m.def(
      "env_task_parameters",
      [](const std::string& task) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (const FieldInfo& p : env_task_parameters(task)) list.push_back(parameter_json(p));
        return py::list(python_of(list));
      },
      py::arg("task"),
      "The options of the task called task: a list of dicts (name as task_options takes it, "
      "kind, unit, range, names, length, optional, default, doc).");
  m.def(
      "env_observations",
      [](const std::string& task) { return ObservationSet::available(*make_env_task(task)); },
      py::arg("task"),
      "Every observation name task can give (built-in, the task's, one 'sensor:NAME' per "
      "sensor). Raises mjarm.Error for an unknown task.");
}

}  // namespace

void bind_env(py::module_& m) {
  bind_env_types(m);
  bind_environment(m);
}

}  // namespace mjarm::python
