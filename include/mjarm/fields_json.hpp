#pragma once
/// @file
/// JSON in and out for declared structs (fields.hpp): every declared field under its name, in
/// declaration order; enums by name, vectors as arrays, nested structs as objects, a non-finite
/// number as null (JSON has no infinity), an optional field without a value as null. Reading is
/// strict: an unknown key gets the closest name, a wrong type says what was expected, and the
/// values are checked against their ranges.

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/fields.hpp"

namespace mjarm {

template <Declared S>
nlohmann::ordered_json fields_to_json(const S& s);

template <Declared S, class Json>
void fields_from_json_at(const Json& j, S& s, std::string_view owner, const std::string& path);

namespace detail {

template <class T>
nlohmann::ordered_json value_to_json(const T& value) {
  if constexpr (std::same_as<T, bool> || std::same_as<T, std::string> || NameListField<T>) {
    return value;
  } else if constexpr (NumberField<T>) {
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(value)) return nullptr;
    }
    return value;
  } else if constexpr (VectorField<T>) {
    auto array = nlohmann::ordered_json::array();
    for (const double x : vector_view(value))
      array.push_back(std::isfinite(x) ? nlohmann::ordered_json(x) : nullptr);
    return array;
  } else if constexpr (OptionalField<T>) {
    return value ? value_to_json(*value) : nlohmann::ordered_json(nullptr);
  } else if constexpr (DeclaredEnum<T>) {
    return to_string(value);
  } else if constexpr (Declared<T>) {
    return fields_to_json(value);
  } else {
    static_assert(sizeof(T) == 0, "a declared field's type has no JSON form");
  }
}

/// A JSON number, or null read as +infinity when the range accepts it.
template <class Json>
double json_number(const Json& j, const std::string& where, const Range& range) {
  if (j.is_null() && range.allow_infinity && range.max == Range::inf) return Range::inf;
  if (!j.is_number()) throw Error(where + " must be a number, got " + std::string(j.type_name()));
  return j.template get<double>();
}

template <class T, class Json>
void value_from_json(const Json& j, T& value, std::string_view owner, const std::string& path,
                     const Range& range) {
  const std::string where = owner_prefix(owner) + path;
  if constexpr (std::same_as<T, bool>) {
    if (!j.is_boolean()) throw Error(where + " must be true or false, got " + j.dump());
    value = j.template get<bool>();
  } else if constexpr (std::same_as<T, std::string>) {
    if (!j.is_string()) throw Error(where + " must be a string, got " + j.dump());
    value = j.template get<std::string>();
  } else if constexpr (NameListField<T>) {
    if (!j.is_array()) throw Error(where + " must be an array of strings, got " + j.dump());
    std::vector<std::string> read;
    for (const auto& each : j) {
      if (!each.is_string()) throw Error(where + " must hold strings, got " + each.dump());
      read.push_back(each.template get<std::string>());
    }
    value = std::move(read);
  } else if constexpr (std::is_integral_v<T>) {
    if (!j.is_number_integer())
      throw Error(where + " must be a whole number, got " + j.dump());
    value = j.template get<T>();
  } else if constexpr (NumberField<T>) {
    value = static_cast<T>(json_number(j, where, range));
  } else if constexpr (VectorField<T>) {
    if (!j.is_array()) throw Error(where + " must be an array of numbers, got " + j.dump());
    constexpr Eigen::Index length = fixed_length<T>();
    if (length >= 0 && static_cast<Eigen::Index>(j.size()) != length) {
      throw Error(where + " must have " + std::to_string(length) + " numbers, got " +
                  std::to_string(j.size()));
    }
    Eigen::VectorXd read(static_cast<Eigen::Index>(j.size()));
    for (std::size_t i = 0; i < j.size(); ++i)
      read[static_cast<Eigen::Index>(i)] = json_number(j[i], where + "[" + std::to_string(i) + "]", range);
    assign_vector(value, read);
  } else if constexpr (OptionalField<T>) {
    if (j.is_null()) {
      value.reset();
    } else {
      typename T::value_type set{};
      if constexpr (detail::is_eigen_vector<typename T::value_type>::value)
        set.setZero();  // Eigen leaves a fixed vector uninitialized
      if (value) set = *value;
      value_from_json(j, set, owner, path, range);
      value = std::move(set);
    }
  } else if constexpr (DeclaredEnum<T>) {
    if (!j.is_string()) throw Error(where + " must be a name, got " + j.dump());
    // "unknown shape 'cube' in gains.json; closest: …; shapes: …"
    const std::string kind = path.substr(path.rfind('.') + 1);
    value = parse_enum<T>(j.template get<std::string>(), kind, owner);
  } else if constexpr (Declared<T>) {
    fields_from_json_at(j, value, owner, path);
  } else {
    static_assert(sizeof(T) == 0, "a declared field's type has no JSON form");
  }
}

}  // namespace detail

/// @p s as a JSON object: every declared field, in order.
template <Declared S>
nlohmann::ordered_json fields_to_json(const S& s) {
  nlohmann::ordered_json object = nlohmann::ordered_json::object();
  for_each_field<S>([&](const auto& f) {
    object[std::string(f.name)] = detail::value_to_json(s.*(f.member));
  });
  return object;
}

/// Reads the fields present in JSON object @p j into @p s (absent ones keep their value); the
/// messages say "owner: path.key …" for each value.
/// @throws Error for a non-object, an unknown key (with the closest), a wrong type
template <Declared S, class Json>
void fields_from_json_at(const Json& j, S& s, std::string_view owner, const std::string& path) {
  const std::string here = path.empty() ? std::string() : path + ".";
  if (!j.is_object()) {
    throw Error(detail::owner_prefix(owner) + (path.empty() ? "the document" : path) +
                " must be an object, got " + j.dump());
  }
  std::vector<std::string> known;
  for_each_field<S>([&](const auto& f) { known.emplace_back(f.name); });
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool found = false;
    for_each_field<S>([&](const auto& f) {
      if (found || f.name != it.key()) return;
      found = true;
      detail::value_from_json(it.value(), s.*(f.member), owner, here + it.key(), f.range);
    });
    if (!found) {
      throw Error(detail::owner_prefix(owner) +
                  unknown_name_message("key", it.key(), known, path));
    }
  }
}

/// Reads JSON object @p j into @p s and checks every field against its range.
/// @param where names the document in messages ("options.json")
/// @throws Error "where: unknown key 'stifness'; closest: stiffness; keys: …", "where: damping
///         must be a number, got string", "where: damping must be finite and ≥ 0 [N·s/m], got -1"
template <Declared S, class Json>
void fields_from_json(const Json& j, S& s, std::string_view where) {
  fields_from_json_at(j, s, where, {});
  check_fields(s, where);
}

}  // namespace mjarm
