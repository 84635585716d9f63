// The viewer's target markers (shared by its drivers).
#include "viewer_driver.hpp"

namespace mjarm::detail {

void add_target_marker(mjvScene& scene, const Pose& X_WT, const Eigen::Vector3d& p_WR,
                       const float rgba[4], double radius) {
  auto add = [&scene](int type, const mjtNum size[3], const Eigen::Vector3d& p,
                      const float color[4]) -> mjvGeom* {
    if (scene.ngeom >= scene.maxgeom) return nullptr;
    mjvGeom* g = scene.geoms + scene.ngeom++;
    const mjtNum pos[3] = {p.x(), p.y(), p.z()};
    mjv_initGeom(g, type, size, pos, nullptr, color);
    g->category = mjCAT_DECOR;
    return g;
  };
  // the target: a translucent ball with its axes (x red, y green, z blue)
  const mjtNum ball[3] = {radius, 0.0, 0.0};
  add(mjGEOM_SPHERE, ball, X_WT.p, rgba);
  const float axis_rgba[3][4] = {
      {0.9f, 0.1f, 0.1f, 1.0f}, {0.1f, 0.8f, 0.1f, 1.0f}, {0.1f, 0.2f, 0.9f, 1.0f}};
  const mjtNum none[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d tip = X_WT.p + 0.08 * X_WT.R.col(i);
    if (mjvGeom* g = add(mjGEOM_CAPSULE, none, X_WT.p, axis_rgba[i])) {
      mjv_connector(g, mjGEOM_CAPSULE, 0.004, X_WT.p.data(), tip.data());
    }
  }
  // the reference the controller tracks: a small yellow ball
  const mjtNum dot[3] = {0.012, 0.0, 0.0};
  const float yellow[4] = {1.0f, 0.85f, 0.1f, 0.8f};
  add(mjGEOM_SPHERE, dot, p_WR, yellow);
}

}  // namespace mjarm::detail
