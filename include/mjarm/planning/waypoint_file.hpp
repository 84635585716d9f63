#pragma once
/// @file
/// Waypoint files for the planner (docs/planning.md, "Waypoint files"): JSON with positions and
/// optional orientations, or CSV rows "x,y,z" or "x,y,z,qw,qx,qy,qz".

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/lie/pose.hpp"

namespace mjarm {

/// One waypoint as written: a position and, optionally, an orientation.
struct WaypointSpec {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< p_WT [m]
  std::optional<Eigen::Vector4d> quaternion;           ///< R_WT as (w, x, y, z), normalised
};

/// The contents of a waypoint file.
struct WaypointPath {
  std::vector<WaypointSpec> waypoints;  ///< in order (at least one)
  std::optional<std::string> frame;     ///< JSON "frame": the site or body to move
  /// JSON "orientation": the orientation of waypoints that give none (default: the start's).
  std::optional<Eigen::Vector4d> orientation;

  /// The poses: each waypoint's own orientation, else `orientation`, else @p R_default.
  std::vector<Pose> poses(const Eigen::Matrix3d& R_default) const;
};

/// The most waypoints a file may hold: 10 000. Every waypoint costs an IK solve and a checked
/// segment; a 2 000 000-row CSV ran for 97 s before failing for another reason.
inline constexpr std::size_t kMaxWaypoints = 10000;

/// Parses JSON text:
/// `{"frame": "attachment_site", "orientation": [w, x, y, z],
///   "waypoints": [{"position": [x, y, z], "quaternion": [w, x, y, z]}, {"position": [...]}]}`
/// ("frame", "orientation" and each "quaternion" optional).
/// @throws Error naming @p source and the waypoint for invalid JSON, a missing or misshapen
///         field, a value that is not a finite number, a zero quaternion, no waypoint, or more
///         than `kMaxWaypoints` (before any is read).
WaypointPath parse_waypoints_json(std::string_view text, std::string_view source = "<string>");

/// Parses CSV text: one waypoint per row, 3 columns (x, y, z [m]) or 7 (… qw, qx, qy, qz); an
/// optional header row starting with a letter; blank lines and lines starting with '#' skipped.
/// @throws Error naming @p source and the line for a wrong column count, a value that is not a
///         finite number (NaN, inf, text), a zero quaternion, no waypoint, or more than
///         `kMaxWaypoints` (at the first row beyond).
WaypointPath parse_waypoints_csv(std::string_view text, std::string_view source = "<string>");

/// Reads @p path: JSON when it ends in ".json", CSV otherwise. The file is read like every user
/// file (`read_user_file`): a regular file of at most 64 MiB, never a FIFO or a device.
/// @throws Error naming the file and what is wrong with it (missing, a symbolic link loop, a
///         folder, a FIFO or device, too large, unreadable), or as the parsers.
WaypointPath load_waypoints(const std::filesystem::path& path);

}  // namespace mjarm
