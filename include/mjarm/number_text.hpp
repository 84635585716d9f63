#pragma once
/// @file
/// How every message of mjarm writes a number: the shortest text that reads back as the same
/// double ("0.1", "1e+308", "-2.5e-07"), so an error never prints 1e308 with 300 digits nor
/// rounds a value the user typed into another one.

#include <optional>
#include <string>
#include <string_view>

namespace mjarm {

/// @p value in its shortest round-trip form (std::to_chars): "0.1", "250", "1e+308",
/// "2.5e-07"; "nan", "inf" and "-inf" spelled out.
std::string number_text(double value);

/// @p value with @p significant_digits significant digits (printf's %.*g: "0.0615712",
/// "1e-08"), for figures read by people rather than read back; "nan", "inf" and "-inf" spelled
/// out.
std::string number_text(double value, int significant_digits);

/// The number @p text spells, whole and nothing else ("0.1", "+2", "-2.5e-07", "inf", "nan";
/// not "0.1 ", "1,5", "0x10", "1e999" or ""), or nothing. The same in every locale.
std::optional<double> number_from_text(std::string_view text);

}  // namespace mjarm
