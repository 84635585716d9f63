#pragma once
/// @file
/// Scene files: the same scene as the C++ `Scene` API, written in YAML (or JSON, which the YAML
/// parser reads too) so a user can compose a scene without C++. Format: docs/scene.md.

#include <filesystem>
#include <string>
#include <string_view>

#include "mjarm/scene/scene.hpp"

namespace mjarm {

/// Reads a scene file. Relative model and mesh paths resolve against the file's directory;
/// the scene is named by the file's `name` key, else the file's stem.
/// @throws Error naming the file, the line and the key for a wrong type, an unknown or repeated
///         key (with the closest keys), a missing required key, a second YAML document, a
///         degenerate frame, or a part the scene refuses.
Scene load_scene_file(const std::filesystem::path& path);

/// Reads scene text; @p source names it in errors, @p base_dir resolves relative paths.
Scene parse_scene(std::string_view text, const std::filesystem::path& base_dir,
                  const std::string& source = "<scene>");

/// Whether @p path names a scene file (extension .yaml, .yml or .json, in any case).
bool is_scene_file(const std::filesystem::path& path);

}  // namespace mjarm
