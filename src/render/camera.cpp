#include "mjarm/render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

constexpr double kRadians = std::numbers::pi / 180.0;

std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

CameraSpec CameraSpec::model_camera(std::string name) {
  CameraSpec spec;
  spec.kind = CameraKind::model;
  spec.name = std::move(name);
  return spec;
}

CameraSpec CameraSpec::free_camera(const Eigen::Vector3d& lookat, double distance, double azimuth,
                                   double elevation) {
  CameraSpec spec;
  spec.kind = CameraKind::free;
  spec.lookat = lookat;
  spec.distance = distance;
  spec.azimuth = azimuth;
  spec.elevation = elevation;
  return spec;
}

CameraSpec CameraSpec::follow(std::string frame, double distance, double azimuth,
                              double elevation) {
  CameraSpec spec;
  spec.kind = CameraKind::follow;
  spec.name = std::move(frame);
  spec.distance = distance;
  spec.azimuth = azimuth;
  spec.elevation = elevation;
  return spec;
}

std::string CameraSpec::describe() const {
  const std::string orbit = "distance " + number(distance) + " m, azimuth " + number(azimuth) +
                            "°, elevation " + number(elevation) + "°";
  switch (kind) {
    case CameraKind::model: return "model camera '" + name + "'";
    case CameraKind::follow: return "follow '" + name + "', " + orbit;
    case CameraKind::free:
      return "free, lookat [" + number(lookat.x()) + ", " + number(lookat.y()) + ", " +
             number(lookat.z()) + "] m, " + orbit;
  }
  return "?";
}

CameraSpec frame_robot(const Robot& robot, const mjData& data, double azimuth,
                       double elevation) {
  const mjModel& m = robot.model();
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper = -lower;
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_bodyid[g] == 0 || m.geom_type[g] == mjGEOM_PLANE) continue;
    const Eigen::Map<const Eigen::Vector3d> p(data.geom_xpos + 3 * g);
    lower = lower.cwiseMin(p - Eigen::Vector3d::Constant(m.geom_rbound[g]));
    upper = upper.cwiseMax(p + Eigen::Vector3d::Constant(m.geom_rbound[g]));
  }
  if (!lower.allFinite() || !upper.allFinite())
    throw Error("cannot frame model '" + robot.name() +
                "': it has no geometry outside the world body; give the camera explicitly");
  const Eigen::Vector3d centre = 0.5 * (lower + upper);
  const double radius = std::max(0.5 * (upper - lower).norm(), 0.05);
  // the sphere fits when distance·tan(fovy/2) ≥ radius; 15 % margin on each side
  const double half = 0.5 * m.vis.global.fovy * kRadians;
  const double distance = 1.15 * radius / std::sin(half);
  const CameraSpec spec = CameraSpec::free_camera(centre, distance, azimuth, elevation);
  free_camera_view(spec.lookat, spec.distance, azimuth, elevation, m.vis.global.fovy);
  return spec;
}

CameraView free_camera_view(const Eigen::Vector3d& lookat, double distance, double azimuth,
                            double elevation, double fovy) {
  if (!lookat.allFinite()) throw Error("camera look-at point must be finite");
  if (!std::isfinite(distance) || !(distance > 0.0))
    throw Error("camera distance must be a finite number > 0 m, got " + number(distance));
  if (!std::isfinite(azimuth)) throw Error("camera azimuth must be finite, got " + number(azimuth));
  if (!std::isfinite(elevation) || !(std::abs(elevation) < 90.0))
    throw Error("camera elevation must be in (-90, 90) degrees (negative looks down), got " +
                number(elevation));
  if (!std::isfinite(fovy) || !(fovy > 0.0 && fovy < 180.0))
    throw Error("camera field of view must be in (0, 180) degrees, got " + number(fovy));
  const double ca = std::cos(azimuth * kRadians), sa = std::sin(azimuth * kRadians);
  const double ce = std::cos(elevation * kRadians), se = std::sin(elevation * kRadians);
  CameraView view;
  view.forward = Eigen::Vector3d(ce * ca, ce * sa, se);
  view.up = Eigen::Vector3d(-se * ca, -se * sa, ce);
  view.position = lookat - distance * view.forward;
  view.fovy = fovy;
  return view;
}

Eigen::Vector3d project(const CameraView& view, int width, int height,
                        const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d r = p_W - view.position;
  const Eigen::Vector3d right = view.forward.cross(view.up);
  const double depth = r.dot(view.forward);
  // symmetric frustum: vertical half-angle from fovy, horizontal from the aspect ratio
  const double tan_y = std::tan(0.5 * view.fovy * kRadians);
  const double tan_x = tan_y * static_cast<double>(width) / static_cast<double>(height);
  const double x_ndc = r.dot(right) / (depth * tan_x);
  const double y_ndc = r.dot(view.up) / (depth * tan_y);
  return {0.5 * (x_ndc + 1.0) * width, 0.5 * (1.0 - y_ndc) * height, depth};
}

}  // namespace mjarm
