#pragma once
// The mesh files a URDF names, checked before MuJoCo opens them (MuJoCo reads URDF itself).

#include <filesystem>
#include <string_view>

namespace mjarm {

/// Checks, with `check_user_file()`, every `<mesh filename>` of the URDF @p xml that exists where
/// MuJoCo looks for it: the file name alone (MuJoCo strips URDF paths, `package://` ones
/// included, unless `<mujoco><compiler strippath="false"/>` says otherwise) under the compiler's
/// `meshdir`, relative to @p base_dir. Missing files are left for MuJoCo to report.
/// @throws Error naming the URDF element, its line and what is wrong with the file.
void check_urdf_assets(std::string_view xml, const std::filesystem::path& base_dir,
                       const std::string& source);

}  // namespace mjarm
