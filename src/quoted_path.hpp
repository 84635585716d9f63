#pragma once
/// @file
/// How the library's error messages name a file or folder (shared by the rooms that write files).

#include <filesystem>
#include <string>

namespace mjarm {

/// @p path in single quotes.
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

}  // namespace mjarm
