#pragma once
/// @file
/// A word as files and command lines write it: the spaces and tabs around it are not part of it
/// (a CSV cell, one number of a comma-separated list).

#include <string_view>

namespace mjarm {

/// @p text without the spaces and tabs at its ends; empty when it holds nothing else.
inline std::string_view without_blanks(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

}  // namespace mjarm
