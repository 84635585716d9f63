#include "mjarm/planning/waypoint_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "blank_trim.hpp"
#include "json_document.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "quoted_path.hpp"

namespace mjarm {

namespace {

Eigen::Vector4d checked_quaternion(const Eigen::Vector4d& q, const std::string& where) {
  const double norm = q.norm();
  if (!(norm > 1e-9)) throw Error(where + ": the quaternion (w, x, y, z) must not be zero");
  return q / norm;
}

/// @p value as N finite numbers, or an error naming @p where.
template <int N>
Eigen::Matrix<double, N, 1> json_numbers(const nlohmann::json& value, const std::string& where) {
  if (!value.is_array() || value.size() != static_cast<std::size_t>(N))
    throw Error(where + " must be an array of " + std::to_string(N) + " numbers");
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    if (!value[i].is_number())
      throw Error(where + " must be an array of " + std::to_string(N) + " numbers");
    out[i] = value[i].get<double>();
    if (!std::isfinite(out[i])) throw Error(where + " holds a value that is not finite");
  }
  return out;
}

/// The number of columns a CSV header names: x, y, z and optionally qw, qx, qy, qz, in that
/// order (any case). A header in another order would mean other numbers than the rows give.
std::size_t checked_header(const std::string& line, const std::string& where) {
  static const std::vector<std::string> kColumns{"x", "y", "z", "qw", "qx", "qy", "qz"};
  std::vector<std::string> names;
  std::istringstream cells(line);
  for (std::string cell; std::getline(cells, cell, ',');) {
    std::string column(without_blanks(cell));
    for (char& c : column) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (std::find(kColumns.begin(), kColumns.end(), column) == kColumns.end())
      throw Error(where + ": " + unknown_name_message("column", column, kColumns, "the header"));
    names.push_back(column);
  }
  std::string given;
  for (std::size_t i = 0; i < names.size(); ++i) given += (i ? ", " : "") + names[i];
  if ((names.size() != 3 && names.size() != 7) ||
      !std::equal(names.begin(), names.end(), kColumns.begin()))
    throw Error(where + ": the header names the columns " + given +
                "; expected x, y, z or x, y, z, qw, qx, qy, qz, in that order");
  return names.size();
}

void require_waypoints(const WaypointPath& path, std::string_view source) {
  if (path.waypoints.empty())
    throw Error("waypoints " + std::string(source) + ": the file holds no waypoint");
}

}  // namespace

std::vector<Pose> WaypointPath::poses(const Eigen::Matrix3d& R_default) const {
  std::vector<Pose> out;
  out.reserve(waypoints.size());
  for (const WaypointSpec& w : waypoints) {
    Pose X;
    if (w.quaternion)
      X = Pose::from_quaternion(w.position, *w.quaternion);
    else if (orientation)
      X = Pose::from_quaternion(w.position, *orientation);
    else
      X.R = R_default;
    X.p = w.position;
    out.push_back(X);
  }
  return out;
}

WaypointPath parse_waypoints_json(std::string_view text, std::string_view source) {
  const std::string name = "waypoints " + std::string(source);
  const JsonDocument json(text, name);
  const nlohmann::json& doc = json.root();
  if (!doc.is_object() || !doc.contains("waypoints"))
    throw Error(name + ": expected an object with \"waypoints\": [{\"position\": [x, y, z]}, …]");
  // a misspelt key would leave its value unused without a word ("quaternoin": the waypoint
  // then takes the path's orientation)
  json.check_keys("", {"frame", "orientation", "waypoints"}, "the file");
  WaypointPath path;
  if (doc.contains("frame")) {
    if (!doc["frame"].is_string())
      throw Error(json.where("", "frame") + ": \"frame\" must be a string");
    path.frame = doc["frame"].get<std::string>();
  }
  if (doc.contains("orientation")) {
    const std::string where = json.where("", "orientation") + ": \"orientation\"";
    path.orientation = checked_quaternion(json_numbers<4>(doc["orientation"], where), where);
  }
  const nlohmann::json& list = doc["waypoints"];
  if (!list.is_array())
    throw Error(json.where("", "waypoints") + ": \"waypoints\" must be an array");
  if (list.size() > kMaxWaypoints)
    throw Error(name + ": " + std::to_string(list.size()) + " waypoints, more than the " +
                std::to_string(kMaxWaypoints) + " a file may hold");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string pointer = "/waypoints/" + std::to_string(k);
    const std::string waypoint = "waypoint " + std::to_string(k);
    const nlohmann::json& w = list[k];
    if (!w.is_object() || !w.contains("position"))
      throw Error(name + ": " + waypoint + " must be an object with \"position\": [x, y, z]");
    json.check_keys(pointer, {"position", "quaternion"}, waypoint);
    WaypointSpec spec;
    spec.position = json_numbers<3>(
        w["position"], json.where(pointer, "position") + ": " + waypoint + " \"position\"");
    if (w.contains("quaternion")) {
      const std::string where = json.where(pointer, "quaternion") + ": " + waypoint;
      spec.quaternion =
          checked_quaternion(json_numbers<4>(w["quaternion"], where + " \"quaternion\""), where);
    }
    path.waypoints.push_back(spec);
  }
  require_waypoints(path, source);
  return path;
}

WaypointPath parse_waypoints_csv(std::string_view text, std::string_view source) {
  const std::string name = "waypoints " + std::string(source);
  WaypointPath path;
  std::istringstream in{std::string(text)};
  std::string line;
  int number = 0;
  bool first_row = true;
  int header_line = 0;
  std::size_t header_columns = 0;  // 0: no header
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const std::string where = name + " line " + std::to_string(number);
    if (first_row && std::isalpha(static_cast<unsigned char>(line[start])) &&
        line.compare(start, 3, "nan") != 0 && line.compare(start, 3, "inf") != 0) {
      first_row = false;
      header_line = number;
      header_columns = checked_header(line, where);
      continue;
    }
    first_row = false;
    if (path.waypoints.size() == kMaxWaypoints)
      throw Error(where + ": a waypoint beyond the " + std::to_string(kMaxWaypoints) +
                  " a file may hold");
    std::vector<double> values;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const auto v = number_from_text(without_blanks(cell));
      if (!v) throw Error(where + ": '" + cell + "' is not a number");
      if (!std::isfinite(*v)) throw Error(where + ": '" + cell + "' is not a finite number");
      values.push_back(*v);
    }
    if (header_columns != 0 && values.size() != header_columns)
      throw Error(where + ": " + std::to_string(values.size()) + " values, but the header (line " +
                  std::to_string(header_line) + ") names " + std::to_string(header_columns) +
                  " columns");
    if (values.size() != 3 && values.size() != 7)
      throw Error(where + ": expected 3 columns (x, y, z) or 7 (x, y, z, qw, qx, qy, qz), got " +
                  std::to_string(values.size()));
    WaypointSpec spec;
    spec.position = Eigen::Vector3d(values[0], values[1], values[2]);
    if (values.size() == 7)
      spec.quaternion =
          checked_quaternion(Eigen::Vector4d(values[3], values[4], values[5], values[6]), where);
    path.waypoints.push_back(spec);
  }
  require_waypoints(path, source);
  return path;
}

WaypointPath load_waypoints(const std::filesystem::path& path) {
  // the one checked reader of user files: regular files only, bounded, never blocking
  const std::string text = read_user_file(path, "waypoint file");
  const std::string source = quoted(path);
  if (has_extension(path, ".json")) return parse_waypoints_json(text, source);
  return parse_waypoints_csv(text, source);
}

}  // namespace mjarm
