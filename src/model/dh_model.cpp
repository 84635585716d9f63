#include "mjarm/model/dh_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

using Transform = Eigen::Matrix4d;

Transform rot_x(double angle) {
  Transform t = Transform::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return t;
}

Transform rot_z(double angle) {
  Transform t = Transform::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

Transform shift(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.block<3, 1>(0, 3) = Eigen::Vector3d(x, y, z);
  return t;
}

/// The row's constant part: where the next joint's frame (standard) or this joint's frame
/// (modified) sits.
Transform row_transform(DhConvention convention, const DhLink& l) {
  if (convention == DhConvention::standard)
    return rot_z(l.theta) * shift(0, 0, l.d) * shift(l.a, 0, 0) * rot_x(l.alpha);
  return rot_x(l.alpha) * shift(l.a, 0, 0) * rot_z(l.theta) * shift(0, 0, l.d);
}

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  for (const double v : values) out += (out.empty() ? "" : " ") + number_text(v);
  return out;
}

/// ` pos="x y z" quat="w x y z"` of transform @p t.
std::string placement(const Transform& t) {
  const Eigen::Quaterniond q(Eigen::Matrix3d(t.block<3, 3>(0, 0)));
  return " pos=\"" + numbers({t(0, 3), t(1, 3), t(2, 3)}) + "\" quat=\"" +
         numbers({q.w(), q.x(), q.y(), q.z()}) + "\"";
}

void check_rigid(const Transform& t, const std::string& what) {
  const Eigen::Matrix3d R = t.block<3, 3>(0, 0);
  if (!t.allFinite() || t.row(3) != Eigen::RowVector4d(0, 0, 0, 1) ||
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-9 || R.determinant() < 0.0) {
    throw Error("DH arm: " + what +
                " must be a rigid transform (orthonormal rotation, last row "
                "0 0 0 1, finite)");
  }
}

void check(const DhArm& arm) {
  check_fields(arm);
  const bool plain_name =
      !arm.name.empty() && std::all_of(arm.name.begin(), arm.name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
      });
  if (!plain_name)
    throw Error("DH arm: name must be letters, digits, _ and -, got '" + arm.name + "'");
  if (arm.links.empty()) throw Error("DH arm: the table has no rows");
  for (std::size_t i = 0; i < arm.links.size(); ++i) {
    const DhLink& l = arm.links[i];
    const std::string row = "DH arm row " + std::to_string(i + 1);
    check_fields(l, row);
    if (!(l.lower < l.upper)) {
      throw Error(row + ": the joint range needs lower < upper, got [" + number_text(l.lower) +
                  ", " + number_text(l.upper) + "]");
    }
  }
  check_rigid(arm.base, "base");
  check_rigid(arm.tool, "tool");
}

/// A capsule of @p mass from the body's origin to @p end (its frame), or a sphere when the link
/// is short.
std::string link_geom(const Eigen::Vector3d& end, double radius, double mass) {
  const std::string size = "size=\"" + number_text(radius) + "\"";
  const std::string weight = " mass=\"" + number_text(mass) + "\"/>";
  if (end.norm() < 1e-6) return "<geom type=\"sphere\" " + size + weight;
  return "<geom type=\"capsule\" " + size + " fromto=\"" +
         numbers({0.0, 0.0, 0.0, end.x(), end.y(), end.z()}) + "\"" + weight;
}

}  // namespace

std::string dh_mjcf(const DhArm& arm) {
  check(arm);
  const std::size_t n = arm.links.size();
  const bool standard = arm.convention == DhConvention::standard;
  // where body i sits in body i−1 (body 0: the world, at the base), and the end site in body n
  std::vector<Transform> place(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Transform before = i == 0 ? arm.base : Transform::Identity();
    place[i] = standard ? (i == 0 ? before : row_transform(arm.convention, arm.links[i - 1]))
                        : before * row_transform(arm.convention, arm.links[i]);
  }
  const Transform end =
      standard ? row_transform(arm.convention, arm.links[n - 1]) * arm.tool : arm.tool;

  std::ostringstream x;
  x << "<mujoco model=\"" << arm.name << "\">\n"
    << "  <compiler angle=\"radian\" autolimits=\"true\"/>\n"
    << "  <option gravity=\"" << (arm.gravity ? "0 0 -9.81" : "0 0 0") << "\"/>\n"
    << "  <default><joint damping=\"" << number_text(arm.damping)
    << "\"/><geom rgba=\"0.7 0.7 0.75 1\"/></default>\n"
    << "  <worldbody>\n";
  std::string indent = "    ";
  for (std::size_t i = 0; i < n; ++i) {
    const DhLink& l = arm.links[i];
    const std::string id = std::to_string(i + 1);
    x << indent << "<body name=\"link" << id << "\"" << placement(place[i]) << ">\n";
    x << indent << "  <joint name=\"joint" << id << "\" type=\""
      << (l.prismatic ? "slide" : "hinge") << "\" axis=\"0 0 1\" range=\""
      << numbers({l.lower, l.upper}) << "\"/>\n";
    const Eigen::Vector3d next = (i + 1 < n ? place[i + 1] : end).block<3, 1>(0, 3);
    x << indent << "  " << link_geom(next, arm.radius, l.mass) << "\n";
    if (l.com || l.inertia) {  // an explicit inertial: MuJoCo takes it over the capsule's
      const Eigen::Vector3d com = l.com.value_or(next / 2.0);
      const double r2 = arm.radius * arm.radius;
      const Eigen::Vector3d inertia = l.inertia.value_or(Eigen::Vector3d(r2, r2, r2) * l.mass);
      x << indent << "  <inertial pos=\"" << numbers({com.x(), com.y(), com.z()}) << "\" mass=\""
        << number_text(l.mass) << "\" diaginertia=\""
        << numbers({inertia.x(), inertia.y(), inertia.z()}) << "\"/>\n";
    }
    indent += "  ";
  }
  x << indent << "<site name=\"end\"" << placement(end) << "/>\n";
  for (std::size_t i = n; i-- > 0;) {
    indent.resize(indent.size() - 2);
    x << indent << "</body>\n";
  }
  x << "  </worldbody>\n";
  if (arm.actuators != DhActuators::none) {
    x << "  <actuator>\n";
    for (std::size_t i = 0; i < n; ++i) {
      const std::string id = std::to_string(i + 1);
      const DhLink& l = arm.links[i];
      if (arm.actuators == DhActuators::motor) {
        x << "    <motor name=\"joint" << id << "\" joint=\"joint" << id << "\" ctrlrange=\""
          << numbers({-arm.effort, arm.effort}) << "\"/>\n";
      } else {
        x << "    <position name=\"joint" << id << "\" joint=\"joint" << id << "\" kp=\""
          << number_text(arm.position_gain) << "\" ctrlrange=\"" << numbers({l.lower, l.upper})
          << "\" forcerange=\"" << numbers({-arm.effort, arm.effort}) << "\"/>\n";
      }
    }
    x << "  </actuator>\n";
  }
  x << "  <keyframe><key name=\"zero\" qpos=\"";
  for (std::size_t i = 0; i < n; ++i)
    x << (i ? " " : "") << number_text(std::clamp(0.0, arm.links[i].lower, arm.links[i].upper));
  x << "\"/></keyframe>\n</mujoco>\n";
  return x.str();
}

Robot dh_robot(const DhArm& arm) { return Robot::from_string(dh_mjcf(arm)); }

}  // namespace mjarm
