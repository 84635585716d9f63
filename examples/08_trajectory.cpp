// 08_trajectory: the motion profiles of trajectory/ — a classic trapezoid, the panda's 7 joints
// blending from a moving state to rest in the shortest quintic that keeps their limits, and an
// end-effector pose path that starts in motion. Each part checks what it prints.

#include <cmath>
#include <cstdio>

#include "mjarm/lie/so3.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

int main() {
  // 1. 0.3 m at the classic defaults (0.18 m/s, 0.9 m/s²)
  const mjarm::TrapezoidProfile trap = mjarm::trap_profile(0.3);
  std::printf("trapezoid: 0.3 m in %.4f s (%s), half way at t = %.4f s: fraction %.3f\n",
              trap.duration(), trap.triangular() ? "triangle" : "trapezoid", trap.duration() / 2,
              mjarm::trap_frac(trap, trap.duration() / 2));

  // 2. the panda's joints, moving, brought to rest at a goal within the limits of its
  //    datasheet (rad/s; a_max 5 rad/s² chosen here)
  Eigen::VectorXd v_max(7), a_max = Eigen::VectorXd::Constant(7, 5.0);
  v_max << 2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61;
  mjarm::QuinticTrajectory::State start{Eigen::VectorXd::Zero(7), Eigen::VectorXd::Zero(7),
                                        Eigen::VectorXd::Zero(7)};
  start.q << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785;
  start.qd << 0.4, -0.2, 0.0, 0.3, 0.0, -0.5, 1.0;
  start.qdd << 1.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0;
  Eigen::VectorXd goal = start.q;
  goal[0] += 1.2;
  goal[3] += 0.6;
  goal[6] -= 0.8;
  const mjarm::QuinticTrajectory::State rest{goal, Eigen::VectorXd::Zero(7),
                                             Eigen::VectorXd::Zero(7)};
  const mjarm::QuinticDuration d = mjarm::shortest_quintic_duration(start, rest, v_max, a_max);
  if (d.status != mjarm::QuinticDurationStatus::ok) {
    std::printf("no duration: %s\n", mjarm::to_string(d.status));
    return 1;
  }
  const mjarm::QuinticTrajectory blend(start, rest, d.duration);
  std::printf("quintic blend: %.4f s, joint %ld meets its %s limit\n", d.duration,
              static_cast<long>(d.limiting_joint),
              d.velocity_limited ? "velocity" : "acceleration");
  for (Eigen::Index i = 0; i < 7; ++i) {
    const mjarm::Quintic::Peaks p = blend.joint(i).peaks();
    std::printf("  joint %ld: peak |qd| %.3f / %.3f rad/s, peak |qdd| %.3f / %.1f rad/s²\n",
                static_cast<long>(i), p.velocity, v_max[i], p.acceleration, a_max[i]);
    if (p.velocity > v_max[i] * (1 + 1e-9) || p.acceleration > a_max[i] * (1 + 1e-9)) return 1;
  }

  // 3. an end-effector pose path starting with a twist [v; ω] (world axes)
  mjarm::Pose X0, X1;
  X0.p << 0.5, 0.0, 0.4;
  X0.R = mjarm::so3::exp(Eigen::Vector3d(3.14159, 0.0, 0.0));  // pointing down
  X1.p << 0.4, 0.2, 0.3;
  X1.R = X0.R * mjarm::so3::exp(Eigen::Vector3d(0.0, 0.0, 0.8));
  mjarm::Vector6d V0;
  V0 << 0.1, 0.0, 0.0, 0.0, 0.6, 0.0;  // turning about world y: not about the rotation's axis
  const mjarm::Se3Interpolation path(X0, V0, mjarm::Vector6d::Zero(), X1, 1.0);
  const mjarm::Se3Interpolation::Sample s0 = path.at(0.0), s1 = path.at(1.0);
  std::printf("SE(3): start twist reproduced to %.1e, goal reached to %.1e m / %.1e rad\n",
              (s0.V_WE - V0).norm(), (s1.X_WE.p - X1.p).norm(),
              mjarm::so3::angle(s1.X_WE.R.transpose() * X1.R));
  return (s0.V_WE - V0).norm() < 1e-12 && (s1.X_WE.p - X1.p).norm() < 1e-12 ? 0 : 1;
}
