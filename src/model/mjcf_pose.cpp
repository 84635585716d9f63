// Orientation attributes of MJCF elements (quat, axisangle, xyaxes, zaxis, euler) as quaternions,
// used to compose <frame> and <replicate> poses into their children.

#include <cctype>
#include <cmath>
#include <numbers>

#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace {

constexpr const char* kOrientationAttrs[] = {"quat", "axisangle", "xyaxes", "zaxis", "euler"};

Quat normalized(Quat q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (n < 1e-300) return {1, 0, 0, 0};
  for (double& x : q) x /= n;
  return q;
}

Vec3 normalized(Vec3 v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n < 1e-300) return v;
  for (double& x : v) x /= n;
  return v;
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Quat axis_angle(const Vec3& axis, double angle) {
  const Vec3 u = normalized(axis);
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), u[0] * s, u[1] * s, u[2] * s};
}

// rotation matrix with columns x, y, z (orthonormal, right-handed) -> quaternion
Quat from_columns(const Vec3& x, const Vec3& y, const Vec3& z) {
  const double t = x[0] + y[1] + z[2];
  Quat q;
  if (t > 0) {
    const double s = 2 * std::sqrt(1 + t);
    q = {s / 4, (y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s};
  } else if (x[0] > y[1] && x[0] > z[2]) {
    const double s = 2 * std::sqrt(1 + x[0] - y[1] - z[2]);
    q = {(y[2] - z[1]) / s, s / 4, (y[0] + x[1]) / s, (z[0] + x[2]) / s};
  } else if (y[1] > z[2]) {
    const double s = 2 * std::sqrt(1 + y[1] - x[0] - z[2]);
    q = {(z[0] - x[2]) / s, (y[0] + x[1]) / s, s / 4, (z[1] + y[2]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + z[2] - x[0] - y[1]);
    q = {(x[1] - y[0]) / s, (z[0] + x[2]) / s, (z[1] + y[2]) / s, s / 4};
  }
  return normalized(q);
}

std::vector<double> exactly(const XmlNode& n, const char* key, std::size_t count) {
  std::vector<double> v = numbers(n, key);
  if (v.size() != count) {
    fail(n, std::string(key) + " needs " + std::to_string(count) + " numbers");
  }
  return v;
}

}  // namespace

Quat quat_mul(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

Vec3 quat_rotate(const Quat& q, const Vec3& v) {
  // v' = v + 2 w (u x v) + 2 u x (u x v), u = vector part
  const Vec3 u{q[1], q[2], q[3]};
  const Vec3 t = cross(u, v);
  const Vec3 t2 = cross(u, t);
  return {v[0] + 2 * (q[0] * t[0] + t2[0]), v[1] + 2 * (q[0] * t[1] + t2[1]),
          v[2] + 2 * (q[0] * t[2] + t2[2])};
}

std::optional<Quat> read_orientation(const XmlNode& n, const Context& ctx) {
  int count = 0;
  for (const char* a : kOrientationAttrs) count += n.has(a) ? 1 : 0;
  if (count == 0) return std::nullopt;
  if (count > 1) fail(n, "more than one orientation attribute (quat/axisangle/xyaxes/zaxis/euler)");
  const double unit = ctx.degrees ? std::numbers::pi / 180.0 : 1.0;

  if (n.has("quat")) {
    const auto v = exactly(n, "quat", 4);
    return normalized(Quat{v[0], v[1], v[2], v[3]});
  }
  if (n.has("axisangle")) {
    const auto v = exactly(n, "axisangle", 4);
    return axis_angle({v[0], v[1], v[2]}, v[3] * unit);
  }
  if (n.has("xyaxes")) {
    const auto v = exactly(n, "xyaxes", 6);
    const Vec3 x = normalized(Vec3{v[0], v[1], v[2]});
    Vec3 y{v[3], v[4], v[5]};
    const double d = dot(x, y);
    y = normalized(Vec3{y[0] - d * x[0], y[1] - d * x[1], y[2] - d * x[2]});
    return from_columns(x, y, cross(x, y));
  }
  if (n.has("zaxis")) {
    const auto v = exactly(n, "zaxis", 3);
    const Vec3 z = normalized(Vec3{v[0], v[1], v[2]});
    // minimal rotation taking the z axis onto z
    const Vec3 axis = cross(Vec3{0, 0, 1}, z);
    const double s = std::sqrt(dot(axis, axis));
    if (s < 1e-12) return z[2] > 0 ? Quat{1, 0, 0, 0} : Quat{0, 1, 0, 0};
    return axis_angle(axis, std::atan2(s, z[2]));
  }
  const auto v = exactly(n, "euler", 3);
  if (ctx.eulerseq.size() != 3) fail(n, "compiler eulerseq must have 3 characters");
  Quat q{1, 0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const char c = ctx.eulerseq[static_cast<std::size_t>(i)];
    const char lc = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const Vec3 axis = lc == 'x' ? Vec3{1, 0, 0} : lc == 'y' ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
    const Quat r = axis_angle(axis, v[static_cast<std::size_t>(i)] * unit);
    // lower case: axes that move with the frame (post-multiply); upper case: fixed axes
    q = std::islower(static_cast<unsigned char>(c)) ? quat_mul(q, r) : quat_mul(r, q);
  }
  return normalized(q);
}

void erase_orientation(XmlNode& n) {
  for (const char* a : kOrientationAttrs) n.erase(a);
}

}  // namespace mjarm::mjcf_detail
