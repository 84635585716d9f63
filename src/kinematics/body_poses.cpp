#include "mjarm/kinematics/body_poses.hpp"

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {

BodyPoses::BodyPoses(const Robot& robot)
    : robot_(robot),
      data_(robot.make_data()),
      poses_(static_cast<std::size_t>(robot.model().nbody)),
      names_(object_names(robot.model(), mjOBJ_BODY)) {
  compute();
}

void BodyPoses::update(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  const mjModel& m = robot_.model();
  if (qpos.size() != m.nq) {
    throw Error("body poses: qpos needs " + std::to_string(m.nq) + " values, got " +
                std::to_string(qpos.size()));
  }
  if (!qpos.allFinite()) throw Error("body poses: qpos must be finite");
  Eigen::Map<Eigen::VectorXd>(data_->qpos, m.nq) = qpos;
  compute();
}

void BodyPoses::update(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const mjModel& m = robot_.model();
  if (&chain.robot().model() != &m)
    throw Error("body poses: the chain belongs to another model than the robot's");
  chain.check(q);
  std::copy(m.qpos0, m.qpos0 + m.nq, data_->qpos);
  chain.scatter(q, data_->qpos);
  compute();
}

const Pose& BodyPoses::pose(std::string_view name) const {
  return poses_[static_cast<std::size_t>(find_object(robot_.model(), mjOBJ_BODY, name))];
}

void BodyPoses::compute() noexcept {
  const mjModel& m = robot_.model();
  mj_kinematics(&m, data_.get());
  for (int b = 0; b < m.nbody; ++b) {
    Pose& X = poses_[static_cast<std::size_t>(b)];
    X.p = Eigen::Map<const Eigen::Vector3d>(data_->xpos + 3 * b);
    X.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(data_->xmat + 9 * b);
  }
}

}  // namespace mjarm
