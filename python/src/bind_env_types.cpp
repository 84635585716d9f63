// env room, the types: ArraySpec (dm_env's specs), the environment options, and the time
// steps (TimeStep, VectorTimeStep, StepType, EpisodeEnd). The environments themselves are in
// bind_env.cpp.
#include <cmath>
#include <limits>
#include <string>

#include "declared_fields.hpp"
#include "env_time_steps.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::python {
namespace {

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
      throw py::value_error(s.name + "[" + std::to_string(i) + "] = " + number_text(x) +
                            " is outside [" + number_text(s.minimum[i]) + ", " +
                            number_text(s.maximum[i]) + "]");
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

const char* kTimeStepDoc =
    "One step of an episode (dm_env's TimeStep): step_type, reward and discount (None on "
    "FIRST), observation (dict name -> float64 array), and end (why the episode ended, on "
    "LAST). The observation is the time step's own copy: it never changes when the environment "
    "steps again, and can be kept as long as wanted. Iterates as (step_type, reward, "
    "discount, observation), like dm_env's namedtuple.";

void bind_array_specs(py::module_& m) {
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
  def_enum<ActionSpace>(m, "ActionSpace",
                        "What one action commands (n = the chain's joints); see docs/env.md.");
  py::class_<ActionOptions> action(m, "ActionOptions", "Bounds and gains of the action spaces.");
  action.def(py::init<>());
  def_fields(action);
  action.def_readwrite("osc", &ActionOptions::osc, "the operational-space controller's options")
      .def("check", &ActionOptions::check, "Raises mjarm.Error naming an option out of range.");
  py::class_<RandomizationOptions> randomization(
      m, "RandomizationOptions",
      "Relative ranges r in [0, 1) of domain randomization: each parameter times a factor "
      "uniform in [1 - r, 1 + r], drawn at every reset.");
  randomization.def(py::init<>());
  def_fields(randomization);
  randomization.def("any", &RandomizationOptions::any, "True when any range is non-zero.");
  py::class_<EnvironmentOptions> environment(
      m, "EnvironmentOptions",
      "Settings of an Environment (checked by its constructor); see docs/env.md. Environment(task, "
      "**overrides) also takes these fields as keywords.");
  environment.def(py::init<>());
  def_fields(environment);
  // the action space also takes its name; the observations are a list of names
  environment
      .def_property(
          "action_space", [](const EnvironmentOptions& o) { return o.action_space; },
          [](EnvironmentOptions& o, py::handle v) {
            o.action_space = py::isinstance<py::str>(v) ? action_space(v.cast<std::string>())
                                                        : v.cast<ActionSpace>();
          },
          "an ActionSpace, or its name ('ee_pose_deltas', ...)")
      .def_readwrite("observations", &EnvironmentOptions::observations,
                     "observation names ([]: the task's defaults); see env_observations(task)");
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
  // a pybind11 enum, not def_enum's enum.Enum: the vectorized batches hold its values as
  // integers, compared with int(mjarm.EpisodeEnd.truncated), which an enum.Enum refuses
  py::enum_<EpisodeEnd> end(m, "EpisodeEnd", "Why an episode ended (set on LAST).");
  for (const auto& n : names_of<EpisodeEnd>()) end.value(n.name.data(), n.value, n.doc.data());

  py::class_<PyTimeStep>(m, "TimeStep", kTimeStepDoc)
      .def_readonly("step_type", &PyTimeStep::step_type, "first, mid or last step of the episode")
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
          return x ? number_text(*x) : std::string("None");
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

}  // namespace

void bind_env_types(py::module_& m) {
  bind_array_specs(m);
  bind_options(m);
  bind_time_steps(m);
}

}  // namespace mjarm::python
