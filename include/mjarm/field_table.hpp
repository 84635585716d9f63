#pragma once
/// @file
/// Declared fields (fields.hpp) as data at run time: every field of a declared struct, nested
/// structs flattened into dotted paths ("criteria.placement_tolerance"), with its kind, unit,
/// range, accepted names, value and doc — what a help text, a sweep file or Python lists — and
/// one field set by its path, from a JSON value or from a word as a command line writes it, with
/// the checks and messages of JSON input (fields_json.hpp).

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/fields_json.hpp"

namespace mjarm {

/// What a field holds.
enum class FieldKind {
  number,   ///< a real number
  integer,  ///< a whole number
  flag,     ///< true or false
  name,     ///< one of an enum's names
  text,     ///< any string
  numbers   ///< numbers in a row (a vector)
};

/// The names (`to_string`, JSON, CLI and Python spelling).
constexpr auto declared_names(const FieldKind*) {
  using E = FieldKind;
  return std::array{EnumName{E::number, "number"}, EnumName{E::integer, "integer"},
                    EnumName{E::flag, "flag"},     EnumName{E::name, "name"},
                    EnumName{E::text, "text"},     EnumName{E::numbers, "numbers"}};
}

/// One field of a declared struct, as data.
struct FieldInfo {
  std::string path;  ///< its name, under its nested structs' names: "criteria.rest_speed"
  FieldKind kind = FieldKind::number;
  std::string unit;                ///< "m/s"; empty when none
  Range range;                     ///< numbers: the values accepted
  std::vector<std::string> names;  ///< name: the enum's names, in order
  Eigen::Index length = -1;        ///< numbers: how many, -1 when it varies
  bool optional = false;           ///< may hold no value: null, "none" on a command line
  std::string doc;                 ///< one line
  nlohmann::ordered_json value;    ///< its value in the struct listed (as fields_to_json writes it)
};

namespace detail {

/// The type a field holds a value of: T, or T for std::optional<T>.
template <class T>
struct value_type_of {
  using type = T;
};
template <class T>
struct value_type_of<std::optional<T>> {
  using type = T;
};

template <class T>
constexpr FieldKind field_kind() {
  if constexpr (OptionalField<T>)
    return field_kind<typename T::value_type>();
  else if constexpr (std::same_as<T, bool>)
    return FieldKind::flag;
  else if constexpr (std::same_as<T, std::string>)
    return FieldKind::text;
  else if constexpr (std::is_integral_v<T>)
    return FieldKind::integer;
  else if constexpr (NumberField<T>)
    return FieldKind::number;
  else if constexpr (VectorField<T>)
    return FieldKind::numbers;
  else
    return FieldKind::name;
}

template <Declared S>
void list_fields(const S& s, const std::string& prefix, std::vector<FieldInfo>& table) {
  for_each_field<S>([&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::Type;
    const std::string path = prefix + std::string(f.name);
    if constexpr (Declared<T>) {
      list_fields(s.*(f.member), path + ".", table);
    } else {
      FieldInfo info;
      info.path = path;
      info.kind = field_kind<T>();
      info.unit = f.unit;
      info.range = f.range;
      using Value = typename detail::value_type_of<T>::type;
      info.optional = OptionalField<T>;
      if constexpr (DeclaredEnum<Value>) info.names = enum_names<Value>();
      if constexpr (VectorField<Value>) info.length = fixed_length<Value>();
      info.doc = f.doc;
      info.value = value_to_json(s.*(f.member));
      table.push_back(std::move(info));
    }
  });
}

/// The JSON value @p text stands for as a field of @p info's kind ("0.1", "inf", "7", "true",
/// "torque", "0.1,0.2,0.3"; "none" for no value of an optional field).
/// @throws Error naming @p where and the field when the word is not of the kind
nlohmann::ordered_json field_text_to_json(const FieldInfo& info, std::string_view text,
                                          std::string_view where);

/// The field at @p path of @p table.
/// @throws Error "where: unknown field 'object-size'; closest: object_size; fields: …"
const FieldInfo& field_at(const std::vector<FieldInfo>& table, std::string_view path,
                          std::string_view where);

/// @p value under the keys of @p path: {"criteria": {"rest_speed": value}} for
/// "criteria.rest_speed".
nlohmann::ordered_json nested_at(std::string_view path, nlohmann::ordered_json value);

/// Sets the field at @p path, which the caller found in @p s's table, through fields_from_json
/// on a copy: @p s changes only when the value is accepted.
template <Declared S>
void set_listed_field(S& s, std::string_view path, const nlohmann::ordered_json& value,
                      std::string_view where) {
  S changed = s;
  fields_from_json(nested_at(path, value), changed, where);
  s = std::move(changed);
}

}  // namespace detail

/// Every field of @p s, nested ones flattened, in declaration order; each with its value in @p s.
template <Declared S>
std::vector<FieldInfo> field_table(const S& s = S{}) {
  std::vector<FieldInfo> table;
  detail::list_fields(s, {}, table);
  return table;
}

/// Sets the field at @p path of @p s to @p value and checks it, as JSON input is read and
/// checked: a number against its range, a name against the enum's names, a vector's length.
/// @param where names the source in messages ("--rest-speed", "sweep.yaml")
/// @throws Error for an unknown path (with the closest), a wrong type or a value out of range;
///         @p s is then unchanged
template <Declared S>
void set_field(S& s, std::string_view path, const nlohmann::ordered_json& value,
               std::string_view where) {
  detail::field_at(field_table(s), path, where);
  detail::set_listed_field(s, path, value, where);
}

/// Sets the field at @p path of @p s from @p text as a command line writes it: a number
/// ("0.02", "1e-3", "inf" where the range takes it), a whole number, true or false, a name, any
/// text, or numbers separated by commas ("0.4,0,0.3"); "none" clears an optional field.
/// @throws Error as `set_field`, or for a word that is not of the field's kind
template <Declared S>
void set_field_text(S& s, std::string_view path, std::string_view text, std::string_view where) {
  const std::vector<FieldInfo> table = field_table(s);
  const FieldInfo& info = detail::field_at(table, path, where);
  detail::set_listed_field(s, path, detail::field_text_to_json(info, text, where), where);
}

}  // namespace mjarm
