#include "mjarm/tasks/docking/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"

namespace mjarm {

namespace {

/// Angle between the peg's axis z_E and the bore's axis −z_S [rad].
double tilt_of(const Pose& X_WE, const Pose& X_WS) {
  const double c = -X_WE.R.col(2).dot(X_WS.R.col(2));
  return std::acos(std::clamp(c, -1.0, 1.0));
}

}  // namespace

DockingInsertion docking_insertion(const Pose& X_WE, const Pose& X_WS) noexcept {
  const Eigen::Vector3d z_S = X_WS.R.col(2);
  const Eigen::Vector3d r = X_WE.p - X_WS.p;
  DockingInsertion in;
  in.depth = -r.dot(z_S);
  in.lateral = (r + in.depth * z_S).norm();
  in.tilt = tilt_of(X_WE, X_WS);
  return in;
}

void check(const DockingCriteria& c) { check_fields(c); }

DockingMetrics evaluate_docking(std::span<const DockingSample> samples, const DockingGoal& goal,
                                const DockingCriteria& criteria) {
  check(criteria);
  DockingMetrics m;
  m.samples = static_cast<int>(samples.size());
  if (samples.empty()) {
    m.failures.push_back("too_short");
    return m;
  }
  const Eigen::Vector3d z_S = goal.X_WS.R.col(2);
  const double t_end = samples.back().t;
  const double t_window = t_end - criteria.window;
  m.min_manipulability = std::numeric_limits<double>::infinity();
  m.min_depth = std::numeric_limits<double>::infinity();
  double sq_position = 0.0, sq_orientation = 0.0;
  int saturated = 0, window = 0, in_contact = 0;
  bool touched = false;
  for (const DockingSample& s : samples) {
    if (!s.finite) {
      m.finite = false;
      continue;
    }
    const Eigen::Vector3d f = s.F_peg.head<3>();
    const Eigen::Vector3d tau = s.F_peg.tail<3>();
    m.peak_force = std::max(m.peak_force, f.norm());
    m.peak_axial_force = std::max(m.peak_axial_force, f.dot(z_S));
    m.peak_wrench = std::max(m.peak_wrench, s.F_peg.norm());
    m.peak_axial_moment = std::max(m.peak_axial_moment, std::abs(tau.dot(z_S)));
    m.max_joint_position = std::max(m.max_joint_position, 100.0 * s.joint_position_ratio);
    m.max_joint_velocity = std::max(m.max_joint_velocity, 100.0 * s.joint_velocity_ratio);
    m.min_manipulability = std::min(m.min_manipulability, s.manipulability);
    if (s.saturated) ++saturated;
    if (!s.within_limits) m.joint_limits_ok = false;
    if (s.other_contact && !m.other_contact) {
      m.other_contact = true;
      m.other_geom1 = s.other_geom1;
      m.other_geom2 = s.other_geom2;
    }
    if (s.contacts > 0 && !touched) {
      touched = true;
      m.first_contact_time = s.t;
    }
    if (!touched) {
      sq_position += (s.X_WE.p - s.X_WD.p).squaredNorm();
      const double angle = so3::angle(s.X_WD.R.transpose() * s.X_WE.R);
      sq_orientation += angle * angle;
      ++m.free_samples;
    }
    if (s.t < t_window - 1e-12) continue;
    // the final window
    ++window;
    const auto [depth, lateral, tilt] = docking_insertion(s.X_WE, goal.X_WS);
    m.steady_axial_force += f.dot(z_S);
    m.steady_wrench += s.F_peg.norm();
    m.steady_lateral += lateral;
    m.steady_tilt += tilt;
    m.max_lateral = std::max(m.max_lateral, lateral);
    m.max_tilt = std::max(m.max_tilt, tilt);
    m.min_depth = std::min(m.min_depth, depth);
    m.max_speed = std::max(m.max_speed, s.V_WE.head<3>().norm());
    m.max_angular_speed = std::max(m.max_angular_speed, s.V_WE.tail<3>().norm());
    if (s.contacts > 0) ++in_contact;
  }
  if (m.free_samples > 0) {
    m.position_rms = std::sqrt(sq_position / m.free_samples);
    m.orientation_rms = std::sqrt(sq_orientation / m.free_samples);
  }
  m.saturation = static_cast<double>(saturated) / static_cast<double>(samples.size());
  if (!std::isfinite(m.min_manipulability)) m.min_manipulability = 0.0;
  if (window > 0) {
    m.steady_axial_force /= window;
    m.steady_wrench /= window;
    m.steady_lateral /= window;
    m.steady_tilt /= window;
    m.contact_fraction = static_cast<double>(in_contact) / window;
  } else {
    m.min_depth = 0.0;
  }

  // the verdict
  auto fail = [&](bool failed, const char* why) {
    if (failed) m.failures.push_back(why);
  };
  const double duration = t_end - samples.front().t;
  fail(duration < criteria.window - 1e-9, "too_short");
  fail(window == 0 || m.min_depth < goal.full_depth - criteria.depth_tolerance, "depth");
  fail(m.max_lateral > criteria.max_lateral, "lateral");
  fail(m.max_tilt > criteria.max_tilt, "tilt");
  fail(m.max_speed > criteria.max_speed || m.max_angular_speed > criteria.max_angular_speed,
       "not_settled");
  fail(m.contact_fraction < criteria.min_contact_fraction, "contact");
  fail(m.peak_force > criteria.max_force, "force");
  fail(m.peak_axial_moment > criteria.max_axial_moment, "axial_moment");
  fail(m.saturation > criteria.max_saturation, "saturation");
  fail(!m.joint_limits_ok, "joint_limit");
  fail(m.other_contact, "other_contact");
  fail(!m.finite, "non_finite");
  m.seated = m.failures.empty();
  return m;
}

DockingProbe::DockingProbe(const DockingScene& scene, const Eigen::VectorXd& max_velocity)
    : chain_(scene.chain),
      peg_(scene.peg),
      socket_(scene.socket),
      tip_(scene.robot.site(DockingNames::tip)),
      max_velocity_(max_velocity),
      q_(scene.chain.size()),
      qd_(scene.chain.size()),
      manipulability_(scene.chain) {
  if (max_velocity.size() != chain_.size())
    throw Error("docking probe: max_velocity needs " + std::to_string(chain_.size()) +
                " entries, got " + std::to_string(max_velocity.size()));
  for (Eigen::Index i = 0; i < max_velocity.size(); ++i)
    if (!(max_velocity[i] > 0.0) || !std::isfinite(max_velocity[i]))
      throw Error("docking probe: max_velocity of joint " + chain_.joint_names()[i] +
                  " must be positive and finite");
}

void DockingProbe::sample(const mjModel& m, const mjData& d, double t, const Pose& X_WD,
                          bool saturated, DockingSample& out) noexcept {
  out.t = t;
  out.X_WD = X_WD;
  out.saturated = saturated;
  out.X_WE.p = Eigen::Map<const Eigen::Vector3d>(d.site_xpos + 3 * tip_);
  out.X_WE.R =
      Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.site_xmat + 9 * tip_);
  mjtNum velocity[6];  // [ω; v], world axes
  mj_objectVelocity(&m, &d, mjOBJ_SITE, tip_, velocity, 0);
  out.V_WE << velocity[3], velocity[4], velocity[5], velocity[0], velocity[1], velocity[2];

  // contacts: the socket's wrench on the peg about the tip; anything else is "other"
  out.F_peg.setZero();
  out.contacts = 0;
  out.other_contact = false;
  out.other_geom1 = out.other_geom2 = -1;
  for (int c = 0; c < d.ncon; ++c) {
    const mjContact& con = d.contact[c];
    if (con.exclude != 0) continue;
    const bool peg1 = peg_.contains(con.geom1), peg2 = peg_.contains(con.geom2);
    const bool socket1 = socket_.contains(con.geom1), socket2 = socket_.contains(con.geom2);
    if (!((peg1 && socket2) || (peg2 && socket1))) {
      if (!out.other_contact) {
        out.other_contact = true;
        out.other_geom1 = con.geom1;
        out.other_geom2 = con.geom2;
      }
      continue;
    }
    ++out.contacts;
    if (con.efc_address < 0) continue;
    mjtNum f_C[6];
    mj_contactForce(&m, &d, c, f_C);
    // the force (and torsional/rolling torque) geom1 exerts on geom2, world axes (rows of
    // frame = contact axes)
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> C(con.frame);
    const double sign = peg2 ? 1.0 : -1.0;
    const Eigen::Vector3d f = sign * (C.transpose() * Eigen::Map<const Eigen::Vector3d>(f_C));
    const Eigen::Vector3d torque =
        sign * (C.transpose() * Eigen::Map<const Eigen::Vector3d>(f_C + 3));
    const Eigen::Vector3d r = Eigen::Map<const Eigen::Vector3d>(con.pos) - out.X_WE.p;
    out.F_peg.head<3>() += f;
    out.F_peg.tail<3>() += r.cross(f) + torque;  // torque: zero for condim 3
  }

  // joints
  const int n = chain_.size();
  out.within_limits = true;
  out.joint_position_ratio = 0.0;
  out.joint_velocity_ratio = 0.0;
  for (int i = 0; i < n; ++i) {
    q_[i] = d.qpos[chain_.qpos_address(i)];
    qd_[i] = d.qvel[chain_.dof_address(i)];
    const double lo = chain_.lower()[i], hi = chain_.upper()[i];
    if (std::isfinite(lo) && std::isfinite(hi) && hi > lo) {
      const double ratio = std::abs(q_[i] - 0.5 * (lo + hi)) / (0.5 * (hi - lo));
      out.joint_position_ratio = std::max(out.joint_position_ratio, ratio);
      if (ratio > 1.0) out.within_limits = false;
    }
    out.joint_velocity_ratio =
        std::max(out.joint_velocity_ratio, std::abs(qd_[i]) / max_velocity_[i]);
  }
  out.finite = out.X_WE.p.allFinite() && out.X_WE.R.allFinite() && out.V_WE.allFinite() &&
               out.F_peg.allFinite() && q_.allFinite() && qd_.allFinite();
  out.manipulability = 0.0;
  if (out.finite) {
    try {
      out.manipulability = manipulability_.evaluate(q_).manipulability;
    } catch (...) {  // finite q never throws; keep the probe noexcept regardless
      out.manipulability = 0.0;
    }
  }
}

}  // namespace mjarm
