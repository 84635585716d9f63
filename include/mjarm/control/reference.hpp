#pragma once

#include <Eigen/Core>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/types.hpp"

namespace mjarm {

/// Desired joint motion, in chain order (each of size chain.size()).
struct JointReference {
  Eigen::VectorXd q;    ///< position [rad or m]
  Eigen::VectorXd qd;   ///< velocity [rad/s or m/s]
  Eigen::VectorXd qdd;  ///< acceleration [rad/s² or m/s²]

  /// The posture @p q_rest at rest (velocity and acceleration zero). Sizes the vectors when their
  /// size differs (the first call); allocates nothing after that.
  void hold(const Eigen::VectorXd& q_rest) {
    if (q.size() != q_rest.size()) {
      q.resize(q_rest.size());
      qd.resize(q_rest.size());
      qdd.resize(q_rest.size());
    }
    q = q_rest;
    qd.setZero();
    qdd.setZero();
  }
};

/// Desired motion of the chain's end-effector frame E, all in world axes.
/// Twists and accelerations are linear first: [v; ω].
struct TaskReference {
  Pose X_WE;                                 ///< desired pose of E in W
  Vector6d V_WE = Vector6d::Zero();          ///< desired velocity of E's origin and angular velocity
  Vector6d A_WE = Vector6d::Zero();          ///< desired acceleration, same layout
  Vector6d F_ext = Vector6d::Zero();         ///< desired wrench exerted on the environment [f; τ] (N, N·m)
};

/// What a controller tracks this tick. A controller reads only the part it needs.
struct Reference {
  JointReference joint;
  TaskReference task;
  double gripper = 0.0;  ///< 0 = fully open, 1 = fully closed
};

}  // namespace mjarm
