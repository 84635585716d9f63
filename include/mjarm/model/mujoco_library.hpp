#pragma once
/// @file
/// The MuJoCo library mjarm runs on: its version and where it was loaded from, checked against
/// the headers mjarm was compiled with.

#include <cstdint>
#include <filesystem>
#include <string>

namespace mjarm {

/// "4.0.1" for MuJoCo's version number 4000001 (`mj_version()`, `mjVERSION_HEADER`:
/// major·10⁶ + minor·10³ + patch).
std::string mujoco_version_text(int version);

/// The file of the MuJoCo library loaded in this process (the one mjarm calls), found from the
/// address of its version string; empty when the loader cannot tell.
std::filesystem::path mujoco_library_path();

/// Refuses a MuJoCo library whose version differs from the headers mjarm was compiled with
/// (a struct layout or a function signature may differ: a crash or silently wrong numbers).
/// The CLI calls it at start, the Python module at import.
/// @throws Error naming both versions, the library's file and what to do.
void check_mujoco_library();

/// MuJoCo warnings raised under mjarm's code in this process so far (each one printed to stderr
/// as "mujoco warning: …" by mjarm's log handler: load warnings, and a simulation's first
/// warning of each kind after a reset, as MuJoCo logs only that one; mjData::warning counts
/// them all). Thread-safe.
std::uint64_t mujoco_warning_count() noexcept;

}  // namespace mjarm
