#pragma once
/// @file
/// Translation of MJCF written for MuJoCo 3.x (e.g. MuJoCo Menagerie arms) into MJCF that the
/// installed MuJoCo 2.2.2 loads. See docs/mjcf_translation.md for every rule and its rationale.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

/// Where one line of a translated document came from.
struct MjcfSourceLine {
  std::filesystem::path file;  ///< the source file; empty for text given without a file name
  int line = 0;                ///< 1-based line of the element in that file
};

/// Result of translate_mjcf().
struct MjcfTranslation {
  /// A complete MJCF document that MuJoCo 2.2.2 accepts. Every asset path in it (mesh, texture,
  /// hfield, skin files) is absolute, so it can be loaded from any directory or from an mjVFS.
  std::string xml;
  /// One human-readable line per rewrite, naming the element it touched, e.g.
  /// `option (line 3): integrator="implicitfast" is MuJoCo 3.x; using "implicit"`.
  /// Empty when the input was already valid MuJoCo 2.2.2 MJCF.
  std::vector<std::string> warnings;
  /// `source_lines[k]` is where line k + 1 of `xml` came from: the file and line of the element
  /// written on it (included files keep their own file and lines).
  std::vector<MjcfSourceLine> source_lines;

  /// @p message (MuJoCo's, about `xml`) with every "line N" / "line = N, column = C" rewritten to
  /// the source: "line 48 of 'arm.xml'" (just "line 48" for text without a file name).
  std::string to_source_lines(std::string_view message) const;
};

/// Rewrites MuJoCo 3.x-only MJCF into MuJoCo 2.2.2 MJCF.
///
/// The input is read with MuJoCo 3.x semantics (autolimits on by default, position actuators with
/// kv / dampratio / inheritrange / timeconst, frames, ...) and written as the equivalent 2.2.2
/// constructs. Constructs 2.2.2 has no counterpart for are dropped with a warning when they do not
/// change the simulated dynamics (visual-only settings, performance flags, new sensor types) and
/// rejected otherwise. `<include file>` elements are resolved recursively by inlining the children
/// of the included file's root (which are translated as well).
///
/// A `dampratio` needs the joint-space inertia at qpos0; it is converted into the exact damping
/// 3.x would compute (kv = 2·dampratio·sqrt(kp·m), m = Σ dof_M0 / moment²) by compiling the
/// translated model once with MuJoCo 2.2.2 (so the assets it references must be readable).
///
/// @param xml       MJCF text; the root element must be `<mujoco>`.
/// @param base_dir  directory of the source file: relative asset paths (compiler meshdir /
///                  texturedir / assetdir, mesh / texture / hfield / skin `file`) and `<include
///                  file>` paths are made absolute against it (an included file in another
///                  directory is also searched relative to itself when the path does not exist
///                  under base_dir).
/// @param source_file  the file @p xml was read from (as the user named it): elements of the main
///                     text are labelled with it in errors, warnings and `source_lines`; empty
///                     for text without a file.
/// @return the translated document, the list of rewrites and the line map.
/// @throws mjarm::Error for malformed XML (with tinyxml2's message and line), an unreadable or
///         cyclic include, or a construct that cannot be translated; the message names the
///         element (tag, name attribute, line, and file for included content).
MjcfTranslation translate_mjcf(std::string_view xml, const std::filesystem::path& base_dir,
                               const std::filesystem::path& source_file = {});

}  // namespace mjarm
