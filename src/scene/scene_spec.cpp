#include "mjarm/scene/scene_spec.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "frame_check.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/finite_model.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

void check_name(const std::string& name, const std::string& what) {
  if (name.empty()) throw Error(what + " needs a non-empty name");
  if (name.find('"') != std::string::npos || name.find('<') != std::string::npos ||
      name.find('&') != std::string::npos)
    throw Error(what + " '" + name + "': a name may not contain '\"', '<' or '&'");
}

// finite, and within the magnitude a compiled model may hold (kMaxModelMagnitude): a position,
// size or mass beyond it makes MuJoCo's first step diverge
void check_finite(std::span<const double> v, const std::string& what) {
  for (double x : v) {
    if (!std::isfinite(x)) throw Error(what + " holds a non-finite value");
    if (std::abs(x) > kMaxModelMagnitude)
      throw Error(what + " holds " + number_text(x) + ", beyond " +
                  number_text(kMaxModelMagnitude) +
                  " (MuJoCo's mjMAXVAL: its state checks call a larger value diverged)");
  }
}

void check_quat(const std::array<double, 4>& q, const std::string& what) {
  scene_detail::check_orientation("quat", q, what);
}

void check_rgba(const std::array<double, 4>& rgba, const std::string& what) {
  for (double c : rgba)
    if (!(c >= 0.0 && c <= 1.0)) throw Error(what + " rgba values must lie in [0, 1]");
}

}  // namespace

ObjectShape object_shape(std::string_view name) {
  return parse_enum<ObjectShape>(name, "object shape");
}

SensorType sensor_type(std::string_view name) {
  return parse_enum<SensorType>(name, "sensor type");
}

void validate(const ArenaSpec& spec) {
  check_finite(spec.floor_half_size, "arena floor_half_size");
  check_finite(spec.table_center, "arena table_center");
  check_finite(spec.table_half_size, "arena table_half_size");
  check_finite(spec.table_friction, "arena table_friction");
  for (double s : spec.floor_half_size)
    if (s <= 0.0) throw Error("arena floor_half_size must be positive");
  if (!spec.table) return;
  for (double s : spec.table_half_size)
    if (s <= 0.0) throw Error("arena table_half_size must be positive");
  check_finite({&spec.table_height, 1}, "arena table_height");
  if (spec.table_height <= 0.05)
    throw Error("arena table_height must be > 0.05 m, got " + number_text(spec.table_height));
  for (double f : spec.table_friction)
    if (f < 0.0) throw Error("arena table_friction must be >= 0");
}

void validate(const RobotSpec& spec) {
  check_name(spec.name, "robot");
  if (spec.name.find('/') != std::string::npos)
    throw Error("robot '" + spec.name + "': a robot name may not contain '/'");
  if (spec.model.empty()) throw Error("robot '" + spec.name + "' needs a model (name or file)");
  check_finite(spec.pos, "robot '" + spec.name + "' pos");
  check_quat(spec.quat, "robot '" + spec.name + "'");
}

void validate(const GripperSpec& spec) {
  check_name(spec.name, "gripper");
  const std::string what = "gripper '" + spec.name + "'";
  if (spec.robot.empty()) throw Error(what + " needs the robot it attaches to");
  if (spec.model.empty()) throw Error(what + " needs a model (name or file)");
  if (spec.frame.empty())
    throw Error(what + " needs the robot frame (site or body) it attaches to");
}

void validate(const ObjectSpec& spec) {
  check_name(spec.name, "object");
  const std::string what = std::string(to_string(spec.shape)) + " object '" + spec.name + "'";
  check_finite(spec.size, what + " size");
  check_finite(spec.pos, what + " pos");
  check_finite(spec.friction, what + " friction");
  check_quat(spec.quat, what);
  check_rgba(spec.rgba, what);
  std::size_t expected = 0;
  switch (spec.shape) {
    case ObjectShape::box:
      expected = 3;
      break;
    case ObjectShape::sphere:
      expected = 1;
      break;
    case ObjectShape::cylinder:
    case ObjectShape::capsule:
      expected = 2;
      break;
    case ObjectShape::mesh:
      expected = spec.size.empty() ? 0 : 3;
      break;
  }
  if (spec.size.size() != expected) {
    throw Error(what + " size expects " + std::to_string(expected) + " value(s) (" +
                (spec.shape == ObjectShape::box      ? "half extents x y z"
                 : spec.shape == ObjectShape::sphere ? "radius"
                 : spec.shape == ObjectShape::mesh   ? "scale x y z, or none"
                                                     : "radius, half length") +
                "), got " + std::to_string(spec.size.size()));
  }
  for (double s : spec.size)
    if (s <= 0.0) throw Error(what + " size must be positive, got " + number_text(s));
  check_finite({&spec.mass, 1}, what + " mass");
  if (spec.mass <= 0.0) throw Error(what + " mass must be positive [kg], got " + number_text(spec.mass));
  for (double f : spec.friction)
    if (f < 0.0) throw Error(what + " friction must be >= 0, got " + number_text(f));
  if (spec.shape == ObjectShape::mesh && spec.mesh_file.empty() == spec.mesh_vertices.empty())
    throw Error(what + " needs a mesh file or its vertices (one of the two)");
  if (spec.shape != ObjectShape::mesh && (!spec.mesh_file.empty() || !spec.mesh_vertices.empty()))
    throw Error(what + " has a mesh but its shape is not mesh");
  if (!spec.mesh_vertices.empty()) {
    check_finite(spec.mesh_vertices, what + " mesh_vertices");
    if (spec.mesh_vertices.size() % 3 != 0 || spec.mesh_vertices.size() < 12)
      throw Error(what + " mesh_vertices must be x y z triples of at least 4 points, got " +
                  std::to_string(spec.mesh_vertices.size()) + " values");
  }
}

void validate(const CompoundFixtureSpec& spec) {
  check_name(spec.name, "fixture");
  const std::string what = "fixture '" + spec.name + "'";
  check_finite(spec.pos, what + " pos");
  check_quat(spec.quat, what);
  if (spec.pieces.empty()) throw Error(what + " has no pieces");
  for (std::size_t i = 0; i < spec.pieces.size(); ++i) {
    const ObjectSpec& piece = spec.pieces[i];
    try {
      validate(piece);
    } catch (const Error& e) {
      throw Error(what + ": " + e.what());
    }
    for (std::size_t j = 0; j < i; ++j)
      if (spec.pieces[j].name == piece.name)
        throw Error(what + ": piece name '" + piece.name + "' is used twice");
  }
}

void validate(const SceneCameraSpec& spec) {
  check_name(spec.name, "camera");
  const std::string what = "camera '" + spec.name + "'";
  check_finite(spec.pos, what + " pos");
  check_quat(spec.quat, what);
  // all zero: not given (the quaternion holds the orientation)
  if (std::any_of(spec.xyaxes.begin(), spec.xyaxes.end(), [](double v) { return v != 0.0; })) {
    scene_detail::check_orientation("xyaxes", spec.xyaxes, what);
    if (spec.quat != std::array<double, 4>{1.0, 0.0, 0.0, 0.0})
      throw Error(what + " has both xyaxes and a quat other than (1, 0, 0, 0): give one");
  }
  if (!std::isfinite(spec.fovy) || spec.fovy <= 0.0 || spec.fovy >= 180.0)
    throw Error(what + " fovy must lie in (0, 180) degrees, got " + number_text(spec.fovy));
}

void validate(const SiteSpec& spec) {
  check_name(spec.name, "site");
  const std::string what = "site '" + spec.name + "'";
  check_finite(spec.pos, what + " pos");
  check_quat(spec.quat, what);
  check_rgba(spec.rgba, what);
  check_finite({&spec.size, 1}, what + " size");
  if (spec.size <= 0.0) throw Error(what + " size must be positive, got " + number_text(spec.size));
}

void validate(const WeldSpec& spec) {
  check_name(spec.name, "weld");
  const std::string what = "weld '" + spec.name + "'";
  if (spec.body1.empty() || spec.body2.empty()) throw Error(what + " needs body1 and body2");
  if (spec.body1 == spec.body2) throw Error(what + " welds body '" + spec.body1 + "' to itself");
  check_finite(spec.solref, what + " solref");
  if (spec.solref[0] <= 0.0 || spec.solref[1] <= 0.0)
    throw Error(what + " solref must be positive (time constant [s], damping ratio)");
}

}  // namespace mjarm
