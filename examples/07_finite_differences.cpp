// 07_finite_differences: the Jacobian of any forward-kinematics function by central differences,
// checked against the analytic Jacobians of the bundled arms in the three frames. Prints the
// largest entry error over N random configurations per arm (default 100; `07_finite_differences
// 1000` for the figures in docs/kinematics.md) and fails when one exceeds 1e-8.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"

int main(int argc, char** argv) {
  const long trials = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 100;
  if (trials < 1 || trials > 1000000) {
    std::fprintf(stderr, "usage: %s [trials, 1 to 1000000]\n", argv[0]);
    return 2;
  }
  const struct {
    const char* model;
    const char* frame;
  } arms[] = {{"panda", "attachment_site"},
              {"ur5e", "attachment_site"},
              {"iiwa14", "attachment_site"},
              {"arm6", "grip"}};
  const mjarm::JacobianFrame frames[] = {mjarm::JacobianFrame::world_aligned,
                                         mjarm::JacobianFrame::local, mjarm::JacobianFrame::world};
  std::mt19937_64 rng(1);
  double overall = 0.0;
  std::printf("max |J - J_fd| over %ld configurations, step 1e-6\n", trials);
  std::printf("%-8s %14s %14s %14s\n", "arm", "world_aligned", "local", "world");
  for (const auto& arm : arms) {
    const mjarm::Robot robot = mjarm::Robot::bundled(arm.model);
    const mjarm::Chain chain(robot, arm.frame);
    mjarm::ChainKinematics kin(chain);
    const int n = chain.size();
    // any function q -> pose will do; here the library's own forward kinematics
    const auto fk = [&kin](const Eigen::VectorXd& q) -> const mjarm::Pose& {
      return kin.update(q);
    };
    mjarm::Matrix6Xd J(6, n), J_fd(6, n);
    mjarm::FiniteDifferenceWorkspace workspace(n, 6);  // no allocation inside the loop
    double worst[3] = {0.0, 0.0, 0.0};
    Eigen::VectorXd q(n);
    for (long t = 0; t < trials; ++t) {
      for (int i = 0; i < n; ++i) {
        q[i] = std::uniform_real_distribution<double>(chain.lower()[i], chain.upper()[i])(rng);
      }
      for (int f = 0; f < 3; ++f) {
        mjarm::finite_difference_pose_jacobian(fk, q, J_fd, workspace, frames[f]);
        kin.update(q);
        kin.jacobian(J, frames[f]);
        worst[f] = std::max(worst[f], (J - J_fd).cwiseAbs().maxCoeff());
      }
    }
    std::printf("%-8s %14.2e %14.2e %14.2e\n", arm.model, worst[0], worst[1], worst[2]);
    overall = std::max({overall, worst[0], worst[1], worst[2]});
  }
  return overall < 1e-8 ? 0 : 1;
}
