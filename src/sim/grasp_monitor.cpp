#include "mjarm/sim/grasp_monitor.hpp"

#include <mujoco/mujoco.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

GeomSet checked_fingers(const GeomSet& set, const char* what) {
  if (set.empty()) throw Error(std::string("grasp monitor: ") + what + " has no geoms");
  return set;
}

}  // namespace

GraspMonitor::GraspMonitor(Simulation& simulation, std::string_view gripper,
                           std::string_view object, const GeomSet& finger1, const GeomSet& finger2,
                           const GraspMonitorOptions& options)
    : simulation_(&simulation), options_(options) {
  check_fields(options);
  if (!(options.drop_distance > options.slip_distance)) {
    throw Error("grasp monitor: drop_distance must be larger than slip_distance [m], got " +
                number_text(options.drop_distance) + " and " +
                number_text(options.slip_distance));
  }
  const mjModel& m = simulation.model();
  gripper_ = find_object(m, mjOBJ_BODY, gripper);
  object_ = find_object(m, mjOBJ_BODY, object);
  const GeomSet object_geoms = GeomSet::of_bodies(simulation.robot(), {std::string(object)}, false);
  if (object_geoms.empty())
    throw Error("grasp monitor: object '" + std::string(object) + "' has no geoms");
  watch1_ = simulation.watch_contacts(checked_fingers(finger1, "finger 1"), object_geoms);
  watch2_ = simulation.watch_contacts(checked_fingers(finger2, "finger 2"), object_geoms);
}

void GraspMonitor::close() noexcept {
  const mjData& d = simulation_->data();
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WG(d.xmat + 9 * gripper_);
  const Eigen::Map<const Eigen::Vector3d> p_WG(d.xpos + 3 * gripper_);
  const Eigen::Map<const Eigen::Vector3d> p_WO(d.xpos + 3 * object_);
  p_GO_ = R_WG.transpose() * (p_WO - p_WG);
  reading_.closed = true;
  reading_.slipped = reading_.dropped = false;
  reading_.slip = reading_.slip_speed = 0.0;
}

void GraspMonitor::open() noexcept {
  reading_.closed = false;
  reading_.slip = reading_.slip_speed = 0.0;
}

GraspEvent GraspMonitor::update() noexcept {
  const ContactSummary& c1 = simulation_->contacts(watch1_);
  const ContactSummary& c2 = simulation_->contacts(watch2_);
  GraspReading& r = reading_;
  r.finger1_contacts = c1.contacts;
  r.finger2_contacts = c2.contacts;
  r.force1_W = c1.force_W;
  r.force2_W = c2.force_W;
  r.force = 0.5 * (c1.force_W - c2.force_W).norm();
  r.load_W = c1.force_W + c2.force_W;
  if (!r.closed) return GraspEvent::none;

  // the object's origin relative to the gripper frame: displacement and velocity
  const mjModel& m = simulation_->model();
  const mjData& d = simulation_->data();
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WG(d.xmat + 9 * gripper_);
  const Eigen::Map<const Eigen::Vector3d> p_WG(d.xpos + 3 * gripper_);
  const Eigen::Map<const Eigen::Vector3d> p_WO(d.xpos + 3 * object_);
  r.slip = (R_WG.transpose() * (p_WO - p_WG) - p_GO_).norm();
  mjtNum vg[6], vo[6];  // [ω; v] at each body frame's origin, world axes
  mj_objectVelocity(&m, &d, mjOBJ_XBODY, gripper_, vg, 0);
  mj_objectVelocity(&m, &d, mjOBJ_XBODY, object_, vo, 0);
  const Eigen::Vector3d w_G(vg[0], vg[1], vg[2]);
  const Eigen::Vector3d v_G(vg[3], vg[4], vg[5]);
  const Eigen::Vector3d v_O(vo[3], vo[4], vo[5]);
  // velocity of the object seen from the gripper frame (rotating with it), world axes
  r.slip_speed = (v_O - v_G - w_G.cross(p_WO - p_WG)).norm();
  if (!r.dropped && r.slip > options_.drop_distance) {
    r.dropped = r.slipped = true;
    return GraspEvent::dropped;
  }
  if (!r.slipped && r.slip > options_.slip_distance) {
    r.slipped = true;
    return GraspEvent::slipped;
  }
  return GraspEvent::none;
}

}  // namespace mjarm
