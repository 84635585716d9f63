#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

TrajectorySample::TrajectorySample(Eigen::Index n)
    : position(Eigen::VectorXd::Zero(n)),
      velocity(Eigen::VectorXd::Zero(n)),
      acceleration(Eigen::VectorXd::Zero(n)),
      jerk(Eigen::VectorXd::Zero(n)) {}

void TrajectorySample::resize(Eigen::Index n) {
  position.resize(n);
  velocity.resize(n);
  acceleration.resize(n);
  jerk.resize(n);
}

}  // namespace mjarm
