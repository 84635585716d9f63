// env room: Environment and VectorEnvironment with dm_env's interface (TimeStep, StepType,
// specs), their options, and the observation layout. The Gymnasium-style adapters are pure
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
#include "mjarm/env/environment.hpp"
#include "mjarm/env/observation_set.hpp"
#include "mjarm/env/task_registry.hpp"
#include "mjarm/env/vector_environment.hpp"

namespace mjarm::python {
namespace {

/// The arrays of an observation as Python sees them: names, offsets and shapes, built once per
/// environment so that a step converts nothing but numbers.
struct ObservationLayout {
  std::vector<py::str> names;
  std::vector<py::ssize_t> offsets;
  std::vector<std::vector<py::ssize_t>> shapes;
  py::ssize_t size = 0;

  explicit ObservationLayout(const ObservationSpec& spec) : size(spec.size()) {
    for (int i = 0; i < spec.count(); ++i) {
      const ArraySpec& a = spec.arrays()[static_cast<std::size_t>(i)];
      names.emplace_back(a.name);
      offsets.push_back(spec.offset(i));
      shapes.emplace_back(a.shape.begin(), a.shape.end());
    }
  }

  /// name → view of @p values (row-major, @p rows rows of `size` values when rows ≥ 0: then
  /// each entry is a contiguous copy of shape (rows, *shape)).
  py::dict dict_of(const py::array_t<double>& values) const {
    py::dict out;
    const double* base = values.data();
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::vector<py::ssize_t> strides(shapes[i].size());
      py::ssize_t stride = sizeof(double);
      for (std::size_t k = shapes[i].size(); k-- > 0;) {
        strides[k] = stride;
        stride *= shapes[i][k];
      }
      out[names[i]] = py::array_t<double>(shapes[i], strides, base + offsets[i], values);
    }
    return out;
  }

  py::dict batch_dict_of(const double* values, py::ssize_t rows) const {
    py::dict out;
    for (std::size_t i = 0; i < names.size(); ++i) {
      std::vector<py::ssize_t> shape{rows};
      py::ssize_t n = 1;
      for (py::ssize_t d : shapes[i]) {
        shape.push_back(d);
        n *= d;
      }
      py::array_t<double> a(shape);
      double* dst = a.mutable_data();
      for (py::ssize_t r = 0; r < rows; ++r)
        std::copy_n(values + r * size + offsets[i], n, dst + r * n);
      out[names[i]] = std::move(a);
    }
    return out;
  }
};

/// A time step handed to Python: it owns a copy of its observation, made at the step; the
/// NumPy array and the dict are built from it on first use (a step that nobody reads costs one
/// copy of a few dozen doubles).
struct PyTimeStep {
  StepType step_type = StepType::first;
  std::optional<double> reward, discount;
  EpisodeEnd end = EpisodeEnd::running;
  std::vector<double> copy;                         // the observation, spec order
  std::shared_ptr<const ObservationLayout> layout;  // names and shapes
  py::object values;                                // float64 array, made from copy on first use
  py::object observation;                           // the dict of views of values, ditto

  const py::object& array() {
    if (!values) {
      values = to_array(copy.data(), static_cast<Eigen::Index>(copy.size()));
      copy = {};
    }
    return values;
  }
};

/// N time steps of a vectorized environment, each array a contiguous copy.
struct PyVectorTimeStep {
  py::array_t<std::int8_t> step_type, end;
  py::array_t<double> reward, discount, values;
  py::dict observation;
};

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

py::tuple shape_tuple(const ArraySpec& s) {
  py::tuple t(s.shape.size());
  for (std::size_t i = 0; i < s.shape.size(); ++i) t[i] = s.shape[i];
  return t;
}

py::array_t<double> shaped(const ArraySpec& s, const Eigen::VectorXd& v) {
  std::vector<py::ssize_t> shape(s.shape.begin(), s.shape.end());
  py::array_t<double> a(shape);
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

std::string spec_shape_text(const std::vector<py::ssize_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

/// dm_env's `Array.validate` / `BoundedArray.validate`: the value as an array of the spec's
/// shape and dtype within its bounds, or a ValueError saying what differs.
py::object validate(const ArraySpec& s, py::handle value) {
  const py::array a = py::module_::import("numpy").attr("asarray")(value);
  std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  const std::vector<py::ssize_t> expected(s.shape.begin(), s.shape.end());
  if (shape != expected) {
    throw py::value_error(s.name + ": expected shape " + spec_shape_text(expected) + ", got " +
                          spec_shape_text(shape));
  }
  if (!a.dtype().is(py::dtype::of<double>())) {
    throw py::value_error(s.name + ": expected dtype float64, got " +
                          py::str(a.dtype()).cast<std::string>());
  }
  const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  for (int i = 0; i < s.size(); ++i) {
    const double x = c.data()[i];
    if (std::isnan(x) || x < s.minimum[i] || x > s.maximum[i]) {
      throw py::value_error(s.name + "[" + std::to_string(i) + "] = " + std::to_string(x) +
                            " is outside [" + std::to_string(s.minimum[i]) + ", " +
                            std::to_string(s.maximum[i]) + "]");
    }
  }
  return py::reinterpret_borrow<py::object>(value);
}

/// A valid value: the minimum where finite, else the maximum where finite, else 0 (dm_env:
/// zeros for an Array, the minimum for a BoundedArray).
py::array_t<double> generate_value(const ArraySpec& s) {
  Eigen::VectorXd v(s.size());
  for (int i = 0; i < s.size(); ++i) {
    v[i] = std::isfinite(s.minimum[i])   ? s.minimum[i]
           : std::isfinite(s.maximum[i]) ? s.maximum[i]
                                         : 0.0;
  }
  return shaped(s, v);
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
                  "randomization, seed, max_acceleration)");
    }
    o.attr(name.c_str()) = value;
  }
  return o.cast<EnvironmentOptions>();
}

const char* kTimeStepDoc =
    "One step of an episode (dm_env's TimeStep): step_type, reward and discount (None on "
    "FIRST), observation (dict name -> float64 array), and end (why the episode ended, on "
    "LAST). The observation is the time step's own copy: it never changes when the environment "
    "steps again, and can be kept as long as wanted. Iterates as (step_type, reward, "
    "discount, observation), like dm_env's namedtuple.";

void bind_specs(py::module_& m) {
  py::class_<ArraySpec>(
      m, "ArraySpec",
      "A named float64 array with its shape and element-wise bounds (dm_env's specs.Array / "
      "specs.BoundedArray: unbounded sides are -inf/+inf). validate() and generate_value() "
      "follow dm_env.")
      .def(py::init([](std::string name, std::vector<int> shape, py::handle minimum,
                       py::handle maximum) {
             ArraySpec s;
             s.name = std::move(name);
             s.shape = std::move(shape);
             const int n = s.size();
             const double inf = std::numeric_limits<double>::infinity();
             s.minimum = minimum.is_none() ? Eigen::VectorXd::Constant(n, -inf)
                                           : to_vector(minimum, "minimum", n);
             s.maximum = maximum.is_none() ? Eigen::VectorXd::Constant(n, inf)
                                           : to_vector(maximum, "maximum", n);
             s.check();
             return s;
           }),
           py::arg("name"), py::arg("shape"), py::arg("minimum") = py::none(),
           py::arg("maximum") = py::none(),
           "A spec of shape `shape` (a list; [] for a scalar); minimum/maximum: size() values "
           "flattened row-major, None for unbounded. Raises mjarm.Error for an empty name, a "
           "non-positive dimension, NaN bounds or minimum > maximum.")
      .def_readonly("name", &ArraySpec::name, "name of the array")
      .def_property_readonly("shape", &shape_tuple, "shape (tuple; () for a scalar)")
      .def_property_readonly(
          "dtype", [](const ArraySpec&) { return py::dtype::of<double>(); },
          "numpy.dtype('float64'): every array of mjarm's environments holds doubles")
      .def_property_readonly(
          "minimum", [](const ArraySpec& s) { return shaped(s, s.minimum); },
          "lower bounds, an array of the spec's shape (-inf where unbounded)")
      .def_property_readonly(
          "maximum", [](const ArraySpec& s) { return shaped(s, s.maximum); },
          "upper bounds, an array of the spec's shape (+inf where unbounded)")
      .def_property_readonly("size", &ArraySpec::size, "number of elements (1 for a scalar)")
      .def("bounded", py::overload_cast<>(&ArraySpec::bounded, py::const_),
           "True when every element has finite bounds on both sides.")
      .def("describe", &ArraySpec::describe, "One line: 'name: float64[7] in [...]'.")
      .def("validate", &validate, py::arg("value"),
           "Returns value when it is a float64 array of the spec's shape within its bounds "
           "(NaN is refused); raises ValueError naming the shape, dtype or the element out of "
           "bounds otherwise (dm_env's validate).")
      .def("generate_value", &generate_value,
           "A valid value of the spec's shape: the minimum where finite, else the maximum where "
           "finite, else 0 (dm_env: zeros for an unbounded Array, the minimum for a "
           "BoundedArray).")
      .def("__repr__", [](const ArraySpec& s) { return "ArraySpec(" + s.describe() + ")"; });
}

void bind_options(py::module_& m) {
  py::enum_<ActionSpace>(m, "ActionSpace",
                         "What one action commands (n = the chain's joints); see docs/env.md.")
      .value("joint_torques", ActionSpace::joint_torques, "n torques [N m], held over the step")
      .value("joint_positions", ActionSpace::joint_positions, "n joint targets [rad]")
      .value("joint_deltas", ActionSpace::joint_deltas, "n increments of the joint target [rad]")
      .value("ee_pose_deltas", ActionSpace::ee_pose_deltas,
             "[dx dy dz rx ry rz] of the goal pose (world axes; m, rotation vector rad)")
      .value("ee_velocities", ActionSpace::ee_velocities,
             "[vx vy vz wx wy wz] (m/s, rad/s), integrated over the step");
  py::class_<ActionOptions>(m, "ActionOptions", "Bounds and gains of the action spaces.")
      .def(py::init<>())
      .def_readwrite("max_joint_delta", &ActionOptions::max_joint_delta,
                     "joint_deltas: |dq| per step [rad or m]")
      .def_readwrite("max_translation", &ActionOptions::max_translation,
                     "ee_pose_deltas: |dp| per axis per step [m]")
      .def_readwrite("max_rotation", &ActionOptions::max_rotation,
                     "ee_pose_deltas: |r| per axis per step [rad]")
      .def_readwrite("max_linear_speed", &ActionOptions::max_linear_speed,
                     "ee_velocities: |v| per axis [m/s]")
      .def_readwrite("max_angular_speed", &ActionOptions::max_angular_speed,
                     "ee_velocities: |w| per axis [rad/s]")
      .def_readwrite("joint_bandwidth", &ActionOptions::joint_bandwidth,
                     "joint PD bandwidth [rad/s]")
      .def_readwrite("max_joint_speed", &ActionOptions::max_joint_speed,
                     "joint speed limit of the differential-IK QP [rad/s or m/s]")
      .def_readwrite("osc", &ActionOptions::osc, "the operational-space controller's options")
      .def("check", &ActionOptions::check, "Raises mjarm.Error naming an option out of range.");
  py::class_<RandomizationOptions>(
      m, "RandomizationOptions",
      "Relative ranges r in [0, 1) of domain randomization: each parameter times a factor "
      "uniform in [1 - r, 1 + r], drawn at every reset.")
      .def(py::init<>())
      .def_readwrite("mass", &RandomizationOptions::mass, "body masses and inertias")
      .def_readwrite("friction", &RandomizationOptions::friction, "geom friction")
      .def_readwrite("damping", &RandomizationOptions::damping, "joint damping")
      .def_readwrite("gain", &RandomizationOptions::gain, "actuator gains")
      .def_readwrite("object_size", &RandomizationOptions::object_size,
                     "the task's object geoms (size, mass, inertia)")
      .def("any", &RandomizationOptions::any, "True when any range is non-zero.");
  py::class_<EnvironmentOptions>(
      m, "EnvironmentOptions",
      "Settings of an Environment (checked by its constructor); see docs/env.md. Environment(task, "
      "**overrides) also takes these fields as keywords.")
      .def(py::init<>())
      .def_property(
          "action_space", [](const EnvironmentOptions& o) { return o.action_space; },
          [](EnvironmentOptions& o, py::handle v) {
            o.action_space = py::isinstance<py::str>(v) ? action_space(v.cast<std::string>())
                                                        : v.cast<ActionSpace>();
          },
          "an ActionSpace, or its name ('ee_pose_deltas', ...)")
      .def_readwrite("action", &EnvironmentOptions::action, "ActionOptions")
      .def_readwrite("control_period", &EnvironmentOptions::control_period,
                     "control step T [s], a whole multiple of the physics timestep")
      .def_readwrite("controller_period", &EnvironmentOptions::controller_period,
                     "low-level controller period [s], a whole divisor of T (0: the action "
                     "space's own)")
      .def_readwrite("time_limit", &EnvironmentOptions::time_limit,
                     "episode length [s]: LAST with discount 1 after ceil(time_limit / T) steps")
      .def_readwrite("observations", &EnvironmentOptions::observations,
                     "observation names ([]: the task's defaults); see env_observations(task)")
      .def_readwrite("refuse_out_of_bounds", &EnvironmentOptions::refuse_out_of_bounds,
                     "refuse (mjarm.Error) instead of clipping an action outside its bounds")
      .def_readwrite("randomization", &EnvironmentOptions::randomization, "RandomizationOptions")
      .def_readwrite("seed", &EnvironmentOptions::seed,
                     "seed of the episode seeds reset() without a seed draws")
      .def_readwrite("max_acceleration", &EnvironmentOptions::max_acceleration,
                     "divergence bound on |qdd| [rad/s^2 or m/s^2]");
  py::class_<ClipCounts>(m, "ClipCounts", "How often actions were clipped into their bounds.")
      .def_readonly("steps", &ClipCounts::steps, "steps with at least one value clipped")
      .def_readonly("values", &ClipCounts::values, "values clipped")
      .def("__repr__", [](const ClipCounts& c) {
        return "ClipCounts(steps=" + std::to_string(c.steps) +
               ", values=" + std::to_string(c.values) + ")";
      });
}

void bind_time_steps(py::module_& m) {
  py::enum_<StepType>(m, "StepType",
                      "Where a time step stands in its episode (dm_env's StepType: FIRST = 0, "
                      "MID = 1, LAST = 2).")
      .value("FIRST", StepType::first, "returned by reset: no reward, no discount")
      .value("MID", StepType::mid, "an ordinary step")
      .value("LAST", StepType::last, "the episode ended (termination or time limit)")
      .def(
          "first", [](StepType t) { return t == StepType::first; }, "True for FIRST.")
      .def(
          "mid", [](StepType t) { return t == StepType::mid; }, "True for MID.")
      .def(
          "last", [](StepType t) { return t == StepType::last; }, "True for LAST.");
  py::enum_<EpisodeEnd>(m, "EpisodeEnd", "Why an episode ended (set on LAST).")
      .value("running", EpisodeEnd::running, "not ended")
      .value("terminated", EpisodeEnd::terminated, "the task ended it: discount 0")
      .value("truncated", EpisodeEnd::truncated, "the time limit: discount 1")
      .value("diverged", EpisodeEnd::diverged, "the physics diverged: discount 0");

  py::class_<PyTimeStep>(m, "TimeStep", kTimeStepDoc)
      .def_readonly("step_type", &PyTimeStep::step_type, "StepType")
      .def_readonly("reward", &PyTimeStep::reward, "float, None on FIRST")
      .def_readonly("discount", &PyTimeStep::discount,
                    "None on FIRST; 0 on a termination or divergence, 1 otherwise (a time-limit "
                    "truncation included)")
      .def_readonly("end", &PyTimeStep::end, "EpisodeEnd: running, or why the episode ended")
      .def_property_readonly(
          "observation",
          [](PyTimeStep& ts) -> py::object {
            if (!ts.observation)
              ts.observation =
                  ts.layout->dict_of(py::reinterpret_borrow<py::array_t<double>>(ts.array()));
            return ts.observation;
          },
          "dict name -> float64 array of the spec's shape, in spec order: views of `values`, "
          "owned by this time step")
      .def_property_readonly(
          "values", &PyTimeStep::array,
          "the whole observation, the spec's arrays back to back (float64, (size,)); "
          "owned by this time step")
      .def(
          "first", [](const PyTimeStep& t) { return t.step_type == StepType::first; },
          "True on the first step of an episode (from reset).")
      .def(
          "mid", [](const PyTimeStep& t) { return t.step_type == StepType::mid; },
          "True on an ordinary step.")
      .def(
          "last", [](const PyTimeStep& t) { return t.step_type == StepType::last; },
          "True on the last step of an episode.")
      .def(
          "__iter__",
          [](py::object self) {
            return py::iter(py::make_tuple(self.attr("step_type"), self.attr("reward"),
                                           self.attr("discount"), self.attr("observation")));
          },
          "(step_type, reward, discount, observation), as dm_env's namedtuple unpacks")
      .def("__len__", [](const PyTimeStep&) { return 4; })
      .def("__repr__", [](const PyTimeStep& t) {
        const auto num = [](const std::optional<double>& x) {
          return x ? std::to_string(*x) : std::string("None");
        };
        std::string type = t.step_type == StepType::first ? "FIRST"
                           : t.step_type == StepType::mid ? "MID"
                                                          : "LAST";
        return "TimeStep(step_type=" + type + ", reward=" + num(t.reward) +
               ", discount=" + num(t.discount) + ", end=" + to_string(t.end) + ")";
      });

  py::class_<PyVectorTimeStep>(
      m, "VectorTimeStep",
      "The time steps of a VectorEnvironment, row i for environment i, each a contiguous array "
      "owned by this object (copies: the next step does not change them).")
      .def_readonly("step_type", &PyVectorTimeStep::step_type,
                    "(N,) int8: StepType values (FIRST 0, MID 1, LAST 2)")
      .def_readonly("reward", &PyVectorTimeStep::reward, "(N,) float64, NaN on FIRST rows")
      .def_readonly("discount", &PyVectorTimeStep::discount, "(N,) float64, NaN on FIRST rows")
      .def_readonly("end", &PyVectorTimeStep::end, "(N,) int8: EpisodeEnd values")
      .def_readonly("values", &PyVectorTimeStep::values,
                    "(N, observation size) float64: each row the spec's arrays back to back")
      .def_readonly("observation", &PyVectorTimeStep::observation,
                    "dict name -> (N, *shape) float64 contiguous array")
      .def(
          "first",
          [](const PyVectorTimeStep& t) {
            return py::array(t.step_type.attr("__eq__")(static_cast<int>(StepType::first)));
          },
          "(N,) bool: rows on FIRST")
      .def(
          "mid",
          [](const PyVectorTimeStep& t) {
            return py::array(t.step_type.attr("__eq__")(static_cast<int>(StepType::mid)));
          },
          "(N,) bool: rows on MID")
      .def(
          "last",
          [](const PyVectorTimeStep& t) {
            return py::array(t.step_type.attr("__eq__")(static_cast<int>(StepType::last)));
          },
          "(N,) bool: rows on LAST");
}

PyEnvironment make_environment(const std::string& task, py::handle options,
                               const py::kwargs& overrides) {
  const EnvironmentOptions o = to_options(options, overrides);
  PyEnvironment e;
  {
    py::gil_scoped_release release;
    e.env = std::make_unique<Environment>(task, o);
  }
  e.layout = std::make_shared<const ObservationLayout>(e.env->observation_spec());
  e.task = task;
  e.action.resize(static_cast<std::size_t>(e.env->action_spec().size()));
  return e;
}

void bind_environment(py::module_& m) {
  py::class_<PyEnvironment>(
      m, "Environment",
      "A learning environment with dm_env's interface on a task (reach, shelf-pick): reset() -> "
      "FIRST, step(action) -> MID or LAST; a time-limit LAST has discount 1 (truncation), a "
      "termination or divergence discount 0. Actions outside their bounds are clipped and "
      "counted (or refused with refuse_out_of_bounds). The GIL is released while it steps. "
      "Not thread-safe: one thread per environment. See docs/env.md and docs/python.md.")
      .def(py::init(&make_environment), py::arg("task"), py::arg("options") = py::none(),
           "Environment(task, options=None, **overrides): the task by name (env_task_names()), "
           "with EnvironmentOptions (None: the defaults) whose fields keyword arguments override "
           "(e.g. time_limit=0.5, action_space='joint_torques'). Raises mjarm.Error for an "
           "unknown task, observation or option, and options out of range.")
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
          "close", [](PyEnvironment&) {},
          "Does nothing (dm_env's interface): memory goes with the object.")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__", [](PyEnvironment&, py::args) { return false; },
          "Leaves a `with` block (close()).")
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
      .def(py::init([](const std::string& task, int count, int threads, py::handle options,
                       const py::kwargs& overrides) {
             const EnvironmentOptions o = to_options(options, overrides);
             PyVectorEnvironment v;
             {
               py::gil_scoped_release release;
               v.env = std::make_unique<VectorEnvironment>(task, o, count, threads);
             }
             v.layout = std::make_shared<const ObservationLayout>(v.env->observation_spec());
             v.task = task;
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
            return v.convert();
          },
          py::arg("actions"),
          "One step of every environment with actions (N, action size); rows whose last step "
          "was LAST are reset instead. Returns a VectorTimeStep. Raises ValueError naming the "
          "expected shape, mjarm.Error for NaN/inf (naming the row) or before reset(); nothing "
          "is stepped then.")
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
      "env_observations",
      [](const std::string& task) { return ObservationSet::available(*make_env_task(task)); },
      py::arg("task"),
      "Every observation name task can give (built-in, the task's, one 'sensor:NAME' per "
      "sensor). Raises mjarm.Error for an unknown task.");
}

}  // namespace

void bind_env(py::module_& m) {
  bind_specs(m);
  bind_options(m);
  bind_time_steps(m);
  bind_environment(m);
}

}  // namespace mjarm::python
