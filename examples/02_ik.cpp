// 02_ik: solve a full-pose target for the bundled Panda with the local pose IK (closed-loop IK
// on the SE(3) log error) and print the joint values, the status and the remaining errors.
// Exits 0 only when the solve converged and an independent forward kinematics agrees.

#include <cstdio>

#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/targets.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/model/robot.hpp"

int main() {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda");
  const mjarm::Chain chain(robot, "attachment_site");

  // the target: 45 cm in front of the base, 40 cm up, tool pointing down, turned 30 degrees
  const mjarm::Pose X_WT = mjarm::Pose::from_rpy(Eigen::Vector3d(0.45, 0.10, 0.40),
                                                 Eigen::Vector3d(3.14159265, 0.0, 0.5236));

  mjarm::PoseIkOptions options;
  options.posture.gain = 0.1;  // among the 1-D family of solutions, prefer mid-range joints
  mjarm::PoseIk ik(chain, options);

  const std::vector<double> home = robot.keyframe_qpos("home");
  const mjarm::IkResult result = ik.solve(X_WT, chain.gather(home.data()));

  std::printf("status     %s after %d iterations\n", mjarm::to_string(result.status),
              result.iterations);
  std::printf("q [rad]   ");
  for (int i = 0; i < result.q.size(); ++i) std::printf(" %7.4f", result.q[i]);
  std::printf("\nposition error    %.2e m\norientation error %.2e rad\n", result.position_error,
              result.orientation_error);

  // check with a fresh kinematics object and the joint limits
  mjarm::ChainKinematics fk(chain);
  const mjarm::FrameErrors check = mjarm::frame_errors(fk.update(result.q), X_WT);
  const bool ok = result.ok() && chain.within_limits(result.q) &&
                  check.position <= options.position_tolerance &&
                  check.orientation <= options.orientation_tolerance;
  std::printf("independent check: %s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
