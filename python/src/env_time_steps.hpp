#pragma once
/// @file
/// The time steps the environment bindings hand to Python (bind_env.cpp makes them,
/// bind_env_types.cpp registers them beside the specs and options). Each owns a copy of its
/// observation: nothing Python keeps can alias the environment's buffer, which the C++
/// `Observation` views only until the next step.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "mjarm/env/array_spec.hpp"
#include "mjarm/env/time_step.hpp"

namespace mjarm::python {

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

/// Registers ArraySpec, the options (ActionSpace, ActionOptions, RandomizationOptions,
/// EnvironmentOptions, ClipCounts) and the time steps (StepType, EpisodeEnd, TimeStep,
/// VectorTimeStep).
void bind_env_types(py::module_& m);

}  // namespace mjarm::python
