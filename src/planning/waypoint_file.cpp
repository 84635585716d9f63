#include "mjarm/planning/waypoint_file.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
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
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(name + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("waypoints"))
    throw Error(name + ": expected an object with \"waypoints\": [{\"position\": [x, y, z]}, …]");
  WaypointPath path;
  if (doc.contains("frame")) {
    if (!doc["frame"].is_string()) throw Error(name + ": \"frame\" must be a string");
    path.frame = doc["frame"].get<std::string>();
  }
  if (doc.contains("orientation"))
    path.orientation =
        checked_quaternion(json_numbers<4>(doc["orientation"], name + ": \"orientation\""),
                           name + ": \"orientation\"");
  const nlohmann::json& list = doc["waypoints"];
  if (!list.is_array()) throw Error(name + ": \"waypoints\" must be an array");
  if (list.size() > kMaxWaypoints)
    throw Error(name + ": " + std::to_string(list.size()) + " waypoints, more than the " +
                std::to_string(kMaxWaypoints) + " a file may hold");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string where = name + ": waypoint " + std::to_string(k);
    const nlohmann::json& w = list[k];
    if (!w.is_object() || !w.contains("position"))
      throw Error(where + " must be an object with \"position\": [x, y, z]");
    WaypointSpec spec;
    spec.position = json_numbers<3>(w["position"], where + " \"position\"");
    if (w.contains("quaternion"))
      spec.quaternion =
          checked_quaternion(json_numbers<4>(w["quaternion"], where + " \"quaternion\""), where);
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
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    if (first_row && std::isalpha(static_cast<unsigned char>(line[start])) &&
        line.compare(start, 3, "nan") != 0 && line.compare(start, 3, "inf") != 0) {
      first_row = false;  // a header
      continue;
    }
    first_row = false;
    const std::string where = name + " line " + std::to_string(number);
    if (path.waypoints.size() == kMaxWaypoints)
      throw Error(where + ": a waypoint beyond the " + std::to_string(kMaxWaypoints) +
                  " a file may hold");
    std::vector<double> values;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const char* begin = cell.c_str();
      char* end = nullptr;
      const double v = std::strtod(begin, &end);
      while (end != nullptr && (*end == ' ' || *end == '\t')) ++end;
      if (end == begin || *end != '\0') throw Error(where + ": '" + cell + "' is not a number");
      if (!std::isfinite(v)) throw Error(where + ": '" + cell + "' is not a finite number");
      values.push_back(v);
    }
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
  if (path.extension() == ".json") return parse_waypoints_json(text, source);
  return parse_waypoints_csv(text, source);
}

}  // namespace mjarm
