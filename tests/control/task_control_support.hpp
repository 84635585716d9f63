#pragma once
// Shared pieces of the task-space controller tests: random panda states and the reference
// quantities written plainly from MuJoCo's own functions (mj_fullM, mj_jacSite, qfrc_bias), so
// that the controllers are checked against formulas that share no code with the library.

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <random>
#include <utility>

#include "mjarm/control/controller.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::test {

using MatrixX = Eigen::MatrixXd;
using VectorX = Eigen::VectorXd;

/// A torque-driven robot, its chain and one mjData.
struct Rig {
  Robot robot;
  Chain chain;
  DataPtr data;
  Rig(const char* model, const char* site)
      : robot(Robot::bundled(model)), chain(robot, site), data(robot.make_data()) {}
  Rig(Robot r, const char* site)
      : robot(std::move(r)), chain(robot, site), data(robot.make_data()) {}
  const mjModel& m() const { return robot.model(); }
  mjData& d() { return *data; }
};

/// Random state within the joint limits (shrunk by 10 %), joint speeds in [−1, 1] rad/s; runs
/// mj_forward. Returns false when the state is in contact (then the caller draws again).
inline bool random_state(Rig& rig, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const mjModel& m = rig.m();
  mjData& d = rig.d();
  mj_resetData(&m, &d);
  for (int i = 0; i < rig.chain.size(); ++i) {
    const double lo = rig.chain.lower()[i], hi = rig.chain.upper()[i];
    const double mid = 0.5 * (lo + hi), half = 0.45 * (hi - lo);
    d.qpos[rig.chain.qpos_address(i)] = mid + half * (2.0 * unit(rng) - 1.0);
    d.qvel[rig.chain.dof_address(i)] = 2.0 * unit(rng) - 1.0;
  }
  mj_forward(&m, &d);
  return d.ncon == 0;
}

/// Dense joint-space inertia from MuJoCo's sparse M (nv×nv).
inline MatrixX dense_mass(const mjModel& m, const mjData& d) {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(m.nv, m.nv);
  mj_fullM(&m, &d, M.data());
  return M;
}

/// mj_jacSite stacked linear first (6×nv), from the positions currently in @p d.
inline MatrixX site_jacobian(const mjModel& m, const mjData& d, int site) {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> jp(3, m.nv), jr(3, m.nv);
  mj_jacSite(&m, &d, jp.data(), jr.data(), site);
  MatrixX J(6, m.nv);
  J << jp, jr;
  return J;
}

/// J̇·q̇ of a site by differentiating mj_jacSite along q̇: central differences of step ε and ε/2
/// combined by Richardson extrapolation (error O(ε⁴)). Uses a scratch copy of @p d.
inline Vector6d site_jdot_qdot(const mjModel& m, const mjData& d, int site, double eps = 1e-3) {
  mjData* s = mj_makeData(&m);
  mj_copyData(s, &m, &d);
  const VectorX qvel = Eigen::Map<const VectorX>(d.qvel, m.nv);
  auto jacobian_at = [&](double h) {
    mju_copy(s->qpos, d.qpos, m.nq);
    mj_integratePos(&m, s->qpos, qvel.data(), h);
    mj_kinematics(&m, s);
    mj_comPos(&m, s);
    return site_jacobian(m, *s, site);
  };
  auto central = [&](double h) -> Vector6d {
    return finite_difference_derivative(jacobian_at, 0.0, h) * qvel;
  };
  const Vector6d coarse = central(eps);
  const Vector6d fine = central(0.5 * eps);
  mj_deleteData(s);
  return (4.0 * fine - coarse) / 3.0;
}

/// Site pose read from @p d.
inline Pose site_pose(const mjData& d, int site) {
  Pose X;
  X.p = Eigen::Map<const Eigen::Vector3d>(d.site_xpos + 3 * site);
  X.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.site_xmat + 9 * site);
  return X;
}

/// e = [p_d − p; rotation vector of R_d·Rᵀ] written with Eigen's AngleAxis.
inline Vector6d reference_error(const Pose& X, const Pose& X_d) {
  Vector6d e;
  e.head<3>() = X_d.p - X.p;
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(X_d.R * X.R.transpose()));
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

/// A random desired pose near @p X: up to @p dp metres and @p dr radians away.
inline Pose nearby_pose(const Pose& X, std::mt19937_64& rng, double dp, double dr) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector3d shift(normal(rng), normal(rng), normal(rng));
  const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Pose X_d;
  X_d.p = X.p + dp * unit(rng) * shift.normalized();
  X_d.R = Eigen::AngleAxisd(dr * unit(rng), axis).toRotationMatrix() * X.R;
  return X_d;
}

/// A random 6-vector with entries in [−s, s].
inline Vector6d random6(std::mt19937_64& rng, double s) {
  std::uniform_real_distribution<double> u(-s, s);
  Vector6d v;
  for (int i = 0; i < 6; ++i) v[i] = u(rng);
  return v;
}

/// Writes @p tau into the chain's motors (gear 1 in the bundled _torque models).
inline void apply_torque(const Chain& chain, const Eigen::VectorXd& tau, mjData& d) {
  for (int i = 0; i < chain.size(); ++i) d.ctrl[*chain.actuator(i)] = tau[i];
}

/// Closed loop on the torque model for @p seconds: mj_step1 → compute → ctrl → mj_step2. Returns
/// the final distance of the frame from the reference position [m].
inline double run_closed_loop(Rig& rig, Controller& controller, const Reference& ref,
                              double seconds) {
  JointCommand command{CommandKind::torque, VectorX::Zero(rig.chain.size())};
  const int steps = static_cast<int>(seconds / rig.m().opt.timestep);
  for (int k = 0; k < steps; ++k) {
    mj_step1(&rig.m(), &rig.d());
    controller.compute(rig.d(), ref, command);
    apply_torque(rig.chain, command.value, rig.d());
    mj_step2(&rig.m(), &rig.d());
  }
  mj_forward(&rig.m(), &rig.d());
  return (site_pose(rig.d(), rig.chain.frame().id).p - ref.task.X_WE.p).norm();
}

}  // namespace mjarm::test
