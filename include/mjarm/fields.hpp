#pragma once
/// @file
/// Declared fields: an options or report struct describes its fields once (name, member, unit,
/// accepted range, one-line doc) and an enum its names once; validation, `to_string` and parsing,
/// JSON (fields_json.hpp), CLI options (app/field_options.hpp) and Python properties
/// (python/src/declared_fields.hpp) are driven from that description.
///
/// A struct declares its fields with a `declared_fields` function found by argument-dependent
/// lookup, next to the struct:
/// @code
/// constexpr auto declared_fields(const SimulationOptions*) {
///   using S = SimulationOptions;
///   return declare<S>("simulation",
///       field("mode", &S::mode, "how the robot moves"),
///       field("control_period", &S::control_period, "s", Range::non_negative(),
///             "control period; 0: one physics step"));
/// }
/// @endcode
/// and an enum its names with `declared_names`:
/// @code
/// constexpr auto declared_names(const SimulationMode*) {
///   return std::array{EnumName{SimulationMode::kinematic, "kinematic"}, …};
/// }
/// @endcode

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

namespace mjarm {

/// The values a numeric field accepts: an interval whose ends may be open, and whether ±infinity
/// belongs to it. NaN never does.
struct Range {
  static constexpr double inf = std::numeric_limits<double>::infinity();

  double min = -inf;
  double max = inf;
  bool min_open = false;        ///< `min` itself is excluded
  bool max_open = false;        ///< `max` itself is excluded
  bool allow_infinity = false;  ///< ±infinity accepted where the interval reaches it

  /// Any finite number.
  static constexpr Range finite() { return {}; }
  /// Greater than zero and finite.
  static constexpr Range positive() { return {0.0, inf, true, false, false}; }
  /// Zero or more, finite.
  static constexpr Range non_negative() { return {0.0, inf, false, false, false}; }
  /// @p low or more, finite.
  static constexpr Range at_least(double low) { return {low, inf, false, false, false}; }
  /// From @p low to @p high, both included.
  static constexpr Range closed(double low, double high) { return {low, high, false, false, false}; }
  /// Above @p low, up to @p high included: (low, high].
  static constexpr Range open_closed(double low, double high) {
    return {low, high, true, false, false};
  }
  /// The same interval with +infinity or −infinity accepted at an end it reaches.
  constexpr Range or_infinity() const {
    Range r = *this;
    r.allow_infinity = true;
    return r;
  }

  /// True when @p v is accepted.
  bool contains(double v) const noexcept {
    if (std::isnan(v)) return false;
    if (std::isinf(v)) return allow_infinity && (v > 0 ? max == inf : min == -inf);
    return (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max);
  }

  /// How messages say the range: "positive and finite", "finite and ≥ 0", "in (0, 1]", "≥ 1" (for
  /// a whole number, @p integer), "positive (+inf allowed)".
  std::string text(bool integer = false) const;
};

/// One declared field of struct @p S: its name (as JSON keys, Python attributes and, with dashes,
/// CLI options spell it), its member, its unit ("s", "N/m", "" when none), the values it accepts
/// (numbers and vectors of numbers only) and a one-line doc.
template <class S, class T>
struct Field {
  using Struct = S;
  using Type = T;
  std::string_view name;
  T S::*member;
  std::string_view unit;
  Range range;
  std::string_view doc;
};

/// A numeric field (a number or a vector of numbers): name, member, unit, range, doc.
template <class S, class T>
constexpr Field<S, T> field(std::string_view name, T S::*member, std::string_view unit,
                            Range range, std::string_view doc) {
  return {name, member, unit, range, doc};
}

/// A field without unit or range (a flag, a name, an enum, a nested declared struct).
template <class S, class T>
constexpr Field<S, T> field(std::string_view name, T S::*member, std::string_view doc) {
  return {name, member, {}, Range{-Range::inf, Range::inf, false, false, true}, doc};
}

/// A report's field (read, not checked): name, member, unit ("" when none), doc.
template <class S, class T>
constexpr Field<S, T> field(std::string_view name, T S::*member, std::string_view unit,
                            std::string_view doc) {
  return {name, member, unit, Range{-Range::inf, Range::inf, false, false, true}, doc};
}

/// The declared fields of struct @p S, in order, and how messages name the struct ("simulation").
template <class S, class... T>
struct FieldList {
  std::string_view owner;
  std::tuple<Field<S, T>...> fields;
};

/// The declaration `declared_fields` returns.
template <class S, class... T>
constexpr FieldList<S, T...> declare(std::string_view owner, Field<S, T>... fields) {
  return {owner, std::tuple<Field<S, T>...>{fields...}};
}

/// A struct that declares its fields.
template <class S>
concept Declared = requires { declared_fields(static_cast<const S*>(nullptr)); };

/// The field list @p S declares.
template <Declared S>
constexpr auto fields_of() {
  return declared_fields(static_cast<const S*>(nullptr));
}

/// Calls @p f(field) for every declared field of @p S, in order.
template <Declared S, class F>
constexpr void for_each_field(F&& f) {
  std::apply([&](const auto&... each) { (f(each), ...); }, fields_of<S>().fields);
}

/// One name of an enum value (its `to_string`, JSON, CLI and Python spelling) and a one-line doc.
template <class E>
struct EnumName {
  E value;
  std::string_view name;
  std::string_view doc = {};
};

// aggregate deduction as clang 14 lacks it: EnumName{E::a, "a"} is an EnumName<E>
template <class E, class... Rest>
EnumName(E, Rest...) -> EnumName<E>;

/// An enum that declares its names.
template <class E>
concept DeclaredEnum =
    std::is_enum_v<E> && requires { declared_names(static_cast<const E*>(nullptr)); };

/// The names @p E declares, in order.
template <DeclaredEnum E>
constexpr auto names_of() {
  return declared_names(static_cast<const E*>(nullptr));
}

/// The name of @p value; "?" for a value the enum does not name (a cast from a bad integer).
template <DeclaredEnum E>
constexpr const char* to_string(E value) noexcept {
  for (const auto& n : names_of<E>())
    if (n.value == value) return n.name.data();
  return "?";
}

/// The value called @p name, or nothing.
template <DeclaredEnum E>
constexpr std::optional<E> enum_from_name(std::string_view name) noexcept {
  for (const auto& n : names_of<E>())
    if (n.name == name) return n.value;
  return std::nullopt;
}

/// Every name of @p E, in declaration order.
template <DeclaredEnum E>
std::vector<std::string> enum_names() {
  std::vector<std::string> names;
  for (const auto& n : names_of<E>()) names.emplace_back(n.name);
  return names;
}

namespace detail {

[[noreturn]] void throw_unknown_enum_name(std::string_view kind, std::string_view word,
                                          const std::vector<std::string>& known,
                                          std::string_view where);
[[noreturn]] void throw_out_of_range(std::string_view owner, std::string_view path,
                                     const Range& range, std::string_view unit, double value,
                                     bool integer);
[[noreturn]] void throw_unnamed_enum(std::string_view owner, std::string_view path, long value);

/// "owner: " or "" when there is no owner.
std::string owner_prefix(std::string_view owner);

template <class T>
struct is_eigen_vector : std::false_type {};
template <int R, int O, int MR>
struct is_eigen_vector<Eigen::Matrix<double, R, 1, O, MR, 1>> : std::true_type {};

template <class T>
struct is_number_array : std::false_type {};
template <std::size_t N>
struct is_number_array<std::array<double, N>> : std::true_type {};
template <>
struct is_number_array<std::vector<double>> : std::true_type {};

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

}  // namespace detail

/// A number field: arithmetic but not bool.
template <class T>
concept NumberField = std::is_arithmetic_v<T> && !std::same_as<T, bool>;

/// A field holding numbers in a row: a column vector of doubles (`Eigen::Vector3d`,
/// `Eigen::VectorXd`, …), a `std::array<double, N>` or a `std::vector<double>`.
template <class T>
concept VectorField = detail::is_eigen_vector<T>::value || detail::is_number_array<T>::value;

/// A field that may hold no value (`std::optional` of a number, a vector or a name): "not set",
/// null in JSON, for a value the code then chooses (drawn from the seed, say).
template <class T>
concept OptionalField = detail::is_optional<T>::value;

/// A field holding a list of names (`std::vector<std::string>`): a report's reasons, say.
template <class T>
concept NameListField = std::same_as<T, std::vector<std::string>>;

/// The length every value of vector field type @p T has; -1 when it varies.
template <VectorField T>
constexpr Eigen::Index fixed_length() {
  if constexpr (detail::is_eigen_vector<T>::value)
    return T::RowsAtCompileTime == Eigen::Dynamic ? -1 : T::RowsAtCompileTime;
  else if constexpr (std::same_as<T, std::vector<double>>)
    return -1;
  else
    return static_cast<Eigen::Index>(std::tuple_size_v<T>);
}

/// The numbers of a vector field, viewed (not copied).
template <VectorField T>
Eigen::Map<const Eigen::VectorXd> vector_view(const T& value) {
  return {value.data(), static_cast<Eigen::Index>(value.size())};
}

/// Sets vector field @p value to @p numbers, whose length the caller checked against
/// `fixed_length<T>()`.
template <VectorField T>
void assign_vector(T& value, const Eigen::Ref<const Eigen::VectorXd>& numbers) {
  if constexpr (detail::is_eigen_vector<T>::value)
    value = numbers;
  else if constexpr (std::same_as<T, std::vector<double>>)
    value.assign(numbers.data(), numbers.data() + numbers.size());
  else
    std::copy(numbers.data(), numbers.data() + numbers.size(), value.begin());
}

/// The value called @p word of @p E.
/// @param kind what the value is ("mode") for the message
/// @param where where the word came from ("--mode", "line 3"), may be empty
/// @throws Error "unknown mode 'torq' in --mode; closest: torque; modes: kinematic, position,
///         torque"
template <DeclaredEnum E>
E parse_enum(std::string_view word, std::string_view kind, std::string_view where = {}) {
  if (const auto value = enum_from_name<E>(word)) return *value;
  detail::throw_unknown_enum_name(kind, word, enum_names<E>(), where);
}

/// Checks one value of field @p f: a number (or each entry of a vector) in the field's range, an
/// enum value the enum names, a nested declared struct field by field.
/// @param owner the struct's name in the message ("simulation"), may be empty
/// @param path the field's path in the message ("controller.stiffness")
/// @throws Error "simulation: control_period must be finite and ≥ 0 [s], got -1"
template <class T>
void check_value(const T& value, std::string_view owner, const std::string& path,
                 std::string_view unit, const Range& range);

/// Checks every declared field of @p s (nested structs included, their paths joined by '.').
/// @param owner the struct's name in messages; by default the one it declares
/// @throws Error naming owner, the field's path, the range, the unit and the value
template <Declared S>
void check_fields(const S& s, std::string_view owner, const std::string& prefix = {}) {
  for_each_field<S>([&](const auto& f) {
    check_value(s.*(f.member), owner, prefix + std::string(f.name), f.unit, f.range);
  });
}

/// Checks every declared field of @p s under the owner name it declares.
template <Declared S>
void check_fields(const S& s) {
  check_fields(s, fields_of<S>().owner);
}

template <class T>
void check_value(const T& value, std::string_view owner, const std::string& path,
                 std::string_view unit, const Range& range) {
  if constexpr (NumberField<T>) {
    if (!range.contains(static_cast<double>(value)))
      detail::throw_out_of_range(owner, path, range, unit, static_cast<double>(value),
                                 std::is_integral_v<T>);
  } else if constexpr (VectorField<T>) {
    const auto numbers = vector_view(value);
    for (Eigen::Index i = 0; i < numbers.size(); ++i) {
      if (!range.contains(numbers[i]))
        detail::throw_out_of_range(owner, path + "[" + std::to_string(i) + "]", range, unit,
                                   numbers[i], false);
    }
  } else if constexpr (OptionalField<T>) {
    if (value) check_value(*value, owner, path, unit, range);
  } else if constexpr (DeclaredEnum<T>) {
    if (!enum_from_name<T>(to_string(value)))
      detail::throw_unnamed_enum(owner, path, static_cast<long>(value));
  } else if constexpr (Declared<T>) {
    check_fields(value, owner, path + ".");
  }
}

}  // namespace mjarm
