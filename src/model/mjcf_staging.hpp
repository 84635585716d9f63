#pragma once
/// @file
/// MJCF staged for loading: one document with every `<include>` inlined and every asset path
/// absolute, each file read or checked through `read_user_file` first (docs/models.md).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

/// Where one line of a staged document came from.
struct MjcfSourceLine {
  std::filesystem::path file;  ///< the source file; empty for text given without a file name
  int line = 0;                ///< 1-based line of the element in that file
};

/// Result of stage_mjcf().
struct StagedMjcf {
  /// The document MuJoCo loads: the user's elements and attributes unchanged, but for the
  /// inlined includes and the absolute asset paths, so it loads from memory (an mjVFS buffer or
  /// an mjSpec) in any directory.
  std::string xml;
  /// `source_lines[k]` is where line k + 1 of `xml` came from: the file and line of the element
  /// written on it (included files keep their own file and lines).
  std::vector<MjcfSourceLine> source_lines;

  /// @p message (MuJoCo's, about `xml`) with every "line N" / "line = N, column = C" rewritten to
  /// the source: "line 48 of 'arm.xml'" (just "line 48" for text without a file name).
  std::string to_source_lines(std::string_view message) const;

  /// With `missing_meshes_as_boxes`: one message per mesh file that was not found, naming it
  /// and what its geoms became.
  std::vector<std::string> missing_meshes;
};

/// Half-size of the box a geom of a missing mesh becomes when the geom gives no size [m].
inline constexpr double kMissingMeshBoxHalfSize = 0.025;

/// Stages MJCF text for loading.
///
/// `<include file>` elements are replaced by the children of the included file's root, recursively
/// (MuJoCo's own semantics: a file is included once, cycles are errors); each included file is
/// read through `read_user_file`. Asset files (mesh, hfield, skin and model `file`, texture
/// `file*`) are made absolute against the compiler's meshdir / texturedir / assetdir and the
/// main file's folder (or the including file's), and checked through `check_user_file`.
///
/// @param xml       MJCF text; the root element must be `<mujoco>`.
/// @param base_dir  folder of the main file: relative include and asset paths resolve against it.
/// @param source_file  the file @p xml was read from (as the user named it): its elements are
///                     labelled with it in errors and `source_lines`; empty for text without a
///                     file.
/// @throws mjarm::Error for malformed XML (with tinyxml2's message and line), an unreadable,
///         missing or cyclic include, or an asset that is missing or not a regular, readable
///         file of a sensible size; the message names the element (tag, name attribute, line
///         and file).
/// @param missing_meshes_as_boxes  a mesh whose file is not found is dropped instead of failing,
///        and every geom that shows it becomes a box (its own size, else
///        kMissingMeshBoxHalfSize): a model drawn from a recording whose meshes are gone.
StagedMjcf stage_mjcf(std::string_view xml, const std::filesystem::path& base_dir,
                      const std::filesystem::path& source_file = {},
                      bool missing_meshes_as_boxes = false);

}  // namespace mjarm
