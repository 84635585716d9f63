#include "mjarm/dynamics/force_torque_sensor.hpp"

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {
namespace {

using SiteRotation = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// address in sensordata of the first sensor of @p type on site @p site, or -1
int sensor_address(const mjModel& m, int type, int site) {
  for (int s = 0; s < m.nsensor; ++s) {
    if (m.sensor_type[s] == type && m.sensor_objtype[s] == mjOBJ_SITE &&
        m.sensor_objid[s] == site) {
      return m.sensor_adr[s];
    }
  }
  return -1;
}

}  // namespace

Vector6d shift_wrench(const Vector6d& F, const Eigen::Vector3d& p_A,
                      const Eigen::Vector3d& p_B) noexcept {
  Vector6d out = F;
  out.tail<3>() += (p_A - p_B).cross(F.head<3>());
  return out;
}

ForceTorqueSensor::ForceTorqueSensor(const Robot& robot, std::string_view site, SensorTiming timing)
    : model_(&robot.model()), site_(site), timing_(timing) {
  const mjModel& m = *model_;
  site_id_ = find_object(m, mjOBJ_SITE, site);
  force_adr_ = sensor_address(m, mjSENS_FORCE, site_id_);
  torque_adr_ = sensor_address(m, mjSENS_TORQUE, site_id_);
  for (const auto& [adr, kind] :
       {std::pair{force_adr_, "force"}, std::pair{torque_adr_, "torque"}}) {
    if (adr < 0) {
      throw Error("site '" + site_ + "' of model '" + robot.name() + "' has no " + kind +
                  " sensor; add <" + kind + " site=\"" + site_ + "\"/> to <sensor>");
    }
  }
}

WrenchReading ForceTorqueSensor::read_site(const mjData& d) const noexcept {
  WrenchReading r;
  r.age = timing_ == SensorTiming::after_step ? model_->opt.timestep : 0.0;
  r.time = d.time - r.age;
  r.wrench << Eigen::Map<const Eigen::Vector3d>(d.sensordata + force_adr_),
      Eigen::Map<const Eigen::Vector3d>(d.sensordata + torque_adr_);
  if (!r.wrench.allFinite()) {
    r.wrench.setZero();
    r.status = WrenchStatus::non_finite;
  }
  return r;
}

WrenchReading ForceTorqueSensor::read_world(const mjData& d,
                                            const Eigen::Vector3d& p_WP) const noexcept {
  WrenchReading r = read_site(d);
  if (!r.ok()) return r;
  const Eigen::Map<const SiteRotation> R_WS(d.site_xmat + 9 * site_id_);
  const Eigen::Map<const Eigen::Vector3d> p_WS(d.site_xpos + 3 * site_id_);
  Vector6d W;
  W << R_WS * r.wrench.head<3>(), R_WS * r.wrench.tail<3>();
  r.wrench = shift_wrench(W, p_WS, p_WP);
  if (!r.wrench.allFinite()) {  // a non-finite site pose
    r.wrench.setZero();
    r.status = WrenchStatus::non_finite;
  }
  return r;
}

WrenchReading ForceTorqueSensor::read_body(const mjData& d, const Pose& X_WE) const noexcept {
  WrenchReading r = read_world(d, X_WE.p);
  if (!r.ok()) return r;
  const Eigen::Vector3d f = X_WE.R.transpose() * r.wrench.head<3>();
  const Eigen::Vector3d tau = X_WE.R.transpose() * r.wrench.tail<3>();
  r.wrench << f, tau;
  return r;
}

}  // namespace mjarm
