#pragma once
/// @file
/// Python enums and properties from declarations (mjarm/fields.hpp): one typed property per
/// field (float, int, bool, str, the enum, an (n,) array, a nested struct), whose docstring says
/// the doc, the unit and the accepted range, so `help()` and the stubs show them.

#include <pybind11/native_enum.h>

#include <string>

#include "bindings.hpp"
#include "mjarm/fields.hpp"

namespace mjarm::python {

/// "doc [unit]; range" for a field's docstring.
template <class F>
std::string field_doc(const F& f) {
  using T = typename F::Type;
  std::string text(f.doc);
  if (!f.unit.empty()) text += " [" + std::string(f.unit) + "]";
  if constexpr (NumberField<T> || VectorField<T>)
    text += "; " + f.range.text(std::is_integral_v<T>);
  return text;
}

/// Defines a read-write property for every declared field of @p S on @p cls.
template <Declared S, class... Extra>
void def_fields(py::class_<S, Extra...>& cls) {
  for_each_field<S>([&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::Type;
    const auto member = f.member;
    const std::string name(f.name);
    const std::string doc = field_doc(f);
    if constexpr (VectorField<T>) {
      // any array-like of numbers, converted and sized like every other argument
      cls.def_property(
          name.c_str(), [member](const S& s) { return Eigen::VectorXd(vector_view(s.*member)); },
          [member, name](S& s, py::handle v) {
            assign_vector(s.*member, to_vector(v, name.c_str(), fixed_length<T>()));
          },
          doc.c_str());
    } else if constexpr (Declared<T>) {
      cls.def_property(
          name.c_str(), [member](S& s) -> T& { return s.*member; },
          [member](S& s, const T& v) { s.*member = v; }, py::return_value_policy::reference_internal,
          doc.c_str());
    } else {
      cls.def_property(
          name.c_str(), [member](const S& s) -> T { return s.*member; },
          [member](S& s, T v) { s.*member = v; }, doc.c_str());
    }
  });
}

/// Defines a read-only property for every declared field of report @p S on @p cls; the
/// docstring says the doc and the unit.
template <Declared S, class... Extra>
void def_readonly_fields(py::class_<S, Extra...>& cls) {
  for_each_field<S>([&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::Type;
    const auto member = f.member;
    std::string doc(f.doc);
    if (!f.unit.empty()) doc += " [" + std::string(f.unit) + "]";
    if constexpr (VectorField<T>) {
      cls.def_property_readonly(
          std::string(f.name).c_str(),
          [member](const S& s) { return Eigen::VectorXd(vector_view(s.*member)); }, doc.c_str());
    } else {
      cls.def_readonly(std::string(f.name).c_str(), member, doc.c_str());
    }
  });
}

/// A Python enum (an `enum.Enum`) of the names @p E declares, each with its doc. Python's own
/// enum type, not a pybind11 class: it compiles in a fraction of the time (a pybind11 enum
/// instantiates its operators and casters per type) and behaves as users expect of an enum
/// (iteration, `E["name"]`, `E(value)`, `.name`, `.value`).
template <DeclaredEnum E>
void def_enum(py::handle scope, const char* name, const char* doc = "") {
  py::native_enum<E> e(scope, name, "enum.Enum", doc);
  for (const auto& n : names_of<E>()) e.value(n.name.data(), n.value, n.doc.data());
  e.finalize();
}

}  // namespace mjarm::python
