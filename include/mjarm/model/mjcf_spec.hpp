#pragma once
/// @file
/// MJCF as an editable `mjSpec` (MuJoCo's model-editing API): a file parsed the way
/// `Robot::from_file` loads it, not compiled, for composing models (the scene room) before
/// `Robot::from_spec` compiles them.

#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace mjarm {

/// Deletes an `mjSpec` with `mj_deleteSpec` (which frees every element in it).
struct SpecDeleter {
  void operator()(mjSpec* spec) const noexcept { mj_deleteSpec(spec); }
};
/// An `mjSpec` owned by its holder.
using SpecPtr = std::unique_ptr<mjSpec, SpecDeleter>;

/// Parses the MJCF file @p path into a spec: read and staged through `stage_mjcf` (includes
/// inlined, asset paths absolute and checked, every file read through `read_user_file`), then
/// parsed by MuJoCo (`mj_parseXMLString`). MuJoCo's parser warnings, if any, are appended to
/// @p warnings when given.
/// @throws Error naming the file for a missing, unreadable or malformed file, a root element
///         other than `<mujoco>`, or MuJoCo's parser error (its line mapped to the user's file).
SpecPtr parse_mjcf_file(const std::filesystem::path& path,
                        std::vector<std::string>* warnings = nullptr);

}  // namespace mjarm
