#include "mjarm/tasks/shelf_pick/video.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {
namespace {

constexpr double kPickMargin = 0.05;  // room around the pick point in the default view [m]

struct Viewpoint {
  double azimuth, elevation;  // [deg]
  double follow_distance;     // [m]
};

// planar2 moves in the x–z plane: look along +y, nearly level; the panda from the front right
Viewpoint viewpoint(const ShelfPickRobot& robot) {
  if (robot.plane_normal) return {90.0, -10.0, 0.9};
  return {150.0, -20.0, 0.8};
}

std::string camera_list(const mjModel& m) {
  std::string list;
  for (const std::string& name : object_names(m, mjOBJ_CAMERA))
    if (!name.empty()) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "none" : list;
}

}  // namespace

CameraSpec shelf_pick_camera(const ShelfPickPlan& plan, const mjData& start,
                             std::string_view camera, double aspect) {
  if (!std::isfinite(aspect) || !(aspect > 0.0))
    throw Error("video camera: the aspect ratio must be > 0, got " + number_text(aspect));
  const mjModel& m = plan.model.model();
  const Viewpoint view = viewpoint(*plan.robot);
  if (camera == "follow")
    return CameraSpec::follow(plan.robot->frame, view.follow_distance, view.azimuth,
                              view.elevation);
  if (!camera.empty()) {
    const std::string name(camera);
    if (mj_name2id(&m, mjOBJ_CAMERA, name.c_str()) < 0)
      throw Error("video camera '" + name + "' is not a camera of model '" + plan.model.name() +
                  "' (its cameras: " + camera_list(m) +
                  "); use one of those, 'follow' (the tool tip) or none (the default view)");
    return CameraSpec::model_camera(name);
  }
  // the box around the robot's geoms (world body and planes excluded) and the pick point
  Eigen::Vector3d lower = plan.pick - Eigen::Vector3d::Constant(kPickMargin);
  Eigen::Vector3d upper = plan.pick + Eigen::Vector3d::Constant(kPickMargin);
  for (int g = 0; g < m.ngeom; ++g) {
    if (m.geom_bodyid[g] == 0 || m.geom_type[g] == mjGEOM_PLANE) continue;
    const Eigen::Map<const Eigen::Vector3d> p(start.geom_xpos + 3 * g);
    lower = lower.cwiseMin(p - Eigen::Vector3d::Constant(m.geom_rbound[g]));
    upper = upper.cwiseMax(p + Eigen::Vector3d::Constant(m.geom_rbound[g]));
  }
  // the closest distance at which every corner of the box is inside the picture (the geoms'
  // bounding spheres leave a margin): for a corner at r from the centre,
  // |r·up| ≤ tan(fovy/2)·(d + r·forward), and likewise across with the aspect ratio
  const Eigen::Vector3d centre = 0.5 * (lower + upper);
  const CameraView axes =
      free_camera_view(centre, 1.0, view.azimuth, view.elevation, m.vis.global.fovy);
  const Eigen::Vector3d right = axes.forward.cross(axes.up);
  const double tan_y = std::tan(0.5 * m.vis.global.fovy * std::numbers::pi / 180.0);
  const double tan_x = tan_y * aspect;
  double distance = 0.1;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d r(corner & 1 ? upper.x() : lower.x(), corner & 2 ? upper.y() : lower.y(),
                            corner & 4 ? upper.z() : lower.z());
    const Eigen::Vector3d d = r - centre;
    distance = std::max({distance, std::abs(d.dot(axes.up)) / tan_y - d.dot(axes.forward),
                         std::abs(d.dot(right)) / tan_x - d.dot(axes.forward)});
  }
  return CameraSpec::free_camera(centre, distance, view.azimuth, view.elevation);
}

}  // namespace mjarm
