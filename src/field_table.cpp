#include "mjarm/field_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "blank_trim.hpp"
#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::detail {

namespace {

[[noreturn]] void refuse(const FieldInfo& info, std::string_view where, const std::string& wanted,
                         std::string_view text) {
  throw Error(owner_prefix(where) + info.path + " must be " + wanted + ", got '" +
              std::string(text) + "'");
}

/// A number as JSON input writes it: +infinity as null, which the reader takes only where the
/// range accepts it; another non-finite value is refused with the range.
nlohmann::ordered_json number_json(const FieldInfo& info, std::string_view word,
                                   std::string_view where) {
  const auto number = number_from_text(word);
  if (!number) refuse(info, where, "a number", word);
  if (std::isfinite(*number)) return *number;
  if (*number > 0 && info.range.allow_infinity && info.range.max == Range::inf) return nullptr;
  throw_out_of_range(where, info.path, info.range, info.unit, *number, false);
}

}  // namespace

nlohmann::ordered_json field_text_to_json(const FieldInfo& info, std::string_view text,
                                          std::string_view where) {
  if (info.optional && text == "none") return nullptr;
  switch (info.kind) {
    case FieldKind::number:
      return number_json(info, text, where);
    case FieldKind::integer: {
      long long value = 0;
      const char* end = text.data() + text.size();
      const auto parsed = std::from_chars(text.data(), end, value);
      if (text.empty() || parsed.ec != std::errc() || parsed.ptr != end)
        refuse(info, where, "a whole number", text);
      return value;
    }
    case FieldKind::flag:
      if (text == "true") return true;
      if (text == "false") return false;
      refuse(info, where, "true or false", text);
    case FieldKind::name:
    case FieldKind::text:
      return std::string(text);
    case FieldKind::numbers: {
      auto numbers = nlohmann::ordered_json::array();
      std::string_view rest = text;
      while (true) {
        const auto comma = rest.find(',');
        numbers.push_back(number_json(info, without_blanks(rest.substr(0, comma)), where));
        if (comma == std::string_view::npos) break;
        rest = rest.substr(comma + 1);
      }
      return numbers;
    }
  }
  refuse(info, where, "a value of a known kind", text);
}

const FieldInfo& field_at(const std::vector<FieldInfo>& table, std::string_view path,
                          std::string_view where) {
  const auto info =
      std::find_if(table.begin(), table.end(), [&](const FieldInfo& i) { return i.path == path; });
  if (info != table.end()) return *info;
  std::vector<std::string> paths;
  for (const FieldInfo& i : table) paths.push_back(i.path);
  throw Error(owner_prefix(where) + unknown_name_message("field", path, paths));
}

nlohmann::ordered_json nested_at(std::string_view path, nlohmann::ordered_json value) {
  for (std::size_t dot; (dot = path.rfind('.')) != std::string_view::npos;
       path = path.substr(0, dot))
    value = nlohmann::ordered_json{{std::string(path.substr(dot + 1)), std::move(value)}};
  return nlohmann::ordered_json{{std::string(path), std::move(value)}};
}

}  // namespace mjarm::detail
