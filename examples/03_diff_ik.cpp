// Differential IK as a QP: the panda's hand follows a target moving on a 10 cm circle for 3 s,
// under joint position and velocity limits, then holds the last pose. Exits 0 when it tracked
// within 1 cm and ended on the target (1e-6 m, 1e-6 rad).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/lie/pose_error.hpp"

int main() {
  using namespace mjarm;
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");

  DiffIkOptions options;
  options.dt = 0.01;                                                      // 100 Hz
  options.velocity_limit = Eigen::VectorXd::Constant(chain.size(), 2.0);  // rad/s
  DiffIk ik(chain, options);
  const int hand = ik.add_pose_task({}, 1.0, 0.5, 0.5);  // position rows weigh more

  const std::vector<double> home = robot.keyframe_qpos("home");
  Eigen::VectorXd q = chain.gather(home.data());
  ChainKinematics kin(chain);
  Pose target = kin.update(q);
  const Eigen::Vector3d center = target.p;

  double worst_tracking = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double t = std::min(k, 300) * options.dt;  // moves for 3 s, then holds
    const double phase = 2.0 * std::numbers::pi * t / 3.0;
    target.p = center + 0.1 * Eigen::Vector3d(0.0, std::sin(phase), 1.0 - std::cos(phase));
    ik.set_target(hand, target);
    q = ik.step(q).q_next;
    const Vector6d e = log_error(kin.update(q), target);
    if (k >= 20) worst_tracking = std::max(worst_tracking, e.head<3>().norm());
  }

  const Vector6d e = log_error(kin.update(q), target);
  std::printf("worst tracking error after 0.2 s: %.2f mm\n", 1e3 * worst_tracking);
  std::printf("final error: position %.3e m, orientation %.3e rad\n", e.head<3>().norm(),
              e.tail<3>().norm());
  std::printf("joints within limits: %s\n", chain.within_limits(q) ? "yes" : "no");
  const bool ok = worst_tracking < 0.01 && e.head<3>().norm() < 1e-6 && e.tail<3>().norm() < 1e-6 &&
                  chain.within_limits(q);
  return ok ? 0 : 1;
}
