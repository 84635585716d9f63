#include "mjarm/kinematics/chain_kinematics.hpp"

#include <cmath>
#include <cstring>

namespace mjarm {
namespace {

Eigen::Matrix3d quat_to_matrix(const double* quat) {
  double mat[9];
  mju_quat2Mat(mat, quat);
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
}

/// Rotation by @p angle about the unit @p axis (Rodrigues).
Eigen::Matrix3d axis_angle(const Eigen::Vector3d& axis, double angle) noexcept {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double t = 1.0 - c;
  Eigen::Matrix3d r;
  const double x = axis.x(), y = axis.y(), z = axis.z();
  r << c + t * x * x, t * x * y - s * z, t * x * z + s * y,  //
      t * x * y + s * z, c + t * y * y, t * y * z - s * x,   //
      t * x * z - s * y, t * y * z + s * x, c + t * z * z;
  return r;
}

}  // namespace

ChainKinematics::ChainKinematics(const Chain& chain) : chain_(chain) {
  const mjModel& m = chain_.robot().model();
  const FrameRef& frame = chain_.frame();
  const int frame_body = frame.kind == FrameKind::site ? m.site_bodyid[frame.id] : frame.id;
  if (frame.kind == FrameKind::site) {
    frame_pos_ = Eigen::Map<const Eigen::Vector3d>(m.site_pos + 3 * frame.id);
    frame_rot_ = quat_to_matrix(m.site_quat + 4 * frame.id);
  } else {
    frame_pos_.setZero();
    frame_rot_.setIdentity();
  }

  // bodies from the world's child down to the frame's body
  std::vector<int> path;
  for (int b = frame_body; b > 0; b = m.body_parentid[b]) path.push_back(b);
  const int n = chain_.size();
  on_path_.assign(n, 0);
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const int b = *it;
    PathBody body;
    body.pos = Eigen::Map<const Eigen::Vector3d>(m.body_pos + 3 * b);
    body.rot = quat_to_matrix(m.body_quat + 4 * b);
    body.first_joint = static_cast<int>(joints_.size());
    body.joint_count = m.body_jntnum[b];
    body.free_root = m.body_jntnum[b] > 0 && m.jnt_type[m.body_jntadr[b]] == mjJNT_FREE;
    for (int j = m.body_jntadr[b]; j < m.body_jntadr[b] + m.body_jntnum[b]; ++j) {
      PathJoint joint;
      joint.type = m.jnt_type[j];
      joint.axis = Eigen::Map<const Eigen::Vector3d>(m.jnt_axis + 3 * j);
      joint.pos = Eigen::Map<const Eigen::Vector3d>(m.jnt_pos + 3 * j);
      joint.qpos_address = m.jnt_qposadr[j];
      joint.qpos0 = m.qpos0[joint.qpos_address];
      joint.at_origin = joint.pos.isZero(0.0);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d unit = Eigen::Vector3d::Unit(k);
        if (joint.axis == unit || joint.axis == -unit) {
          joint.unit_axis = k;
          joint.unit_sign = joint.axis[k];
        }
      }
      for (int i = 0; i < n; ++i) {
        if (chain_.joint_id(i) == j) {
          joint.chain_index = i;
          on_path_[i] = 1;
          path_order_.push_back(i);
        }
      }
      joints_.push_back(joint);
    }
    bodies_.push_back(body);
  }
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  axes_.assign(n, Eigen::Vector3d::Zero());
  anchors_.assign(n, Eigen::Vector3d::Zero());
  last_q_ = Eigen::VectorXd::Zero(n);
}

void ChainKinematics::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
  current_ = false;
}

const Pose& ChainKinematics::update(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  if (current_ && q.size() == last_q_.size() &&
      std::memcmp(q.data(), last_q_.data(), sizeof(double) * static_cast<std::size_t>(q.size())) ==
          0)
    return X_WE_;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const PathBody& body : bodies_) {
    if (body.free_root) {
      // a free joint places its body directly in the world
      const double* qf = fixed_qpos_.data() + joints_[body.first_joint].qpos_address;
      double quat[4] = {qf[3], qf[4], qf[5], qf[6]};
      mju_normalize4(quat);
      p = Eigen::Vector3d(qf[0], qf[1], qf[2]);
      R = quat_to_matrix(quat);
      continue;
    }
    p += R * body.pos;
    R = R * body.rot;
    for (int k = body.first_joint; k < body.first_joint + body.joint_count; ++k) {
      const PathJoint& joint = joints_[k];
      const double value =
          joint.chain_index >= 0 ? q[joint.chain_index] : fixed_qpos_[joint.qpos_address];
      // a joint at the body origin about a coordinate axis (the usual case) skips the products
      // with zeros and ones: the same values
      const Eigen::Vector3d anchor = joint.at_origin ? p : Eigen::Vector3d(R * joint.pos + p);
      const Eigen::Vector3d axis = joint.unit_axis >= 0
                                       ? Eigen::Vector3d(joint.unit_sign * R.col(joint.unit_axis))
                                       : Eigen::Vector3d(R * joint.axis);
      if (joint.chain_index >= 0) {
        axes_[joint.chain_index] = axis;
        anchors_[joint.chain_index] = anchor;
      }
      if (joint.type == mjJNT_HINGE) {
        if (joint.unit_axis >= 0) {
          // R·Rot(±e_k, θ) turns columns i, j = k+1, k+2 (cyclic) by ±θ and keeps column k
          const double angle = joint.unit_sign * (value - joint.qpos0);
          const double c = std::cos(angle);
          const double s = std::sin(angle);
          const int i = (joint.unit_axis + 1) % 3;
          const int j = (joint.unit_axis + 2) % 3;
          const Eigen::Vector3d col_i = R.col(i);
          const Eigen::Vector3d col_j = R.col(j);
          R.col(i) = c * col_i + s * col_j;
          R.col(j) = c * col_j - s * col_i;
        } else {
          R = R * axis_angle(joint.axis, value - joint.qpos0);
        }
        if (!joint.at_origin) p = anchor - R * joint.pos;
      } else if (joint.type == mjJNT_SLIDE) {
        p += axis * (value - joint.qpos0);
      } else if (joint.type == mjJNT_BALL) {
        const double* qb = fixed_qpos_.data() + joint.qpos_address;
        double quat[4] = {qb[0], qb[1], qb[2], qb[3]};
        mju_normalize4(quat);
        R = R * quat_to_matrix(quat);
        p = anchor - R * joint.pos;
      }
    }
  }
  X_WE_.p = p + R * frame_pos_;
  X_WE_.R = R * frame_rot_;
  if (q.size() == last_q_.size()) {
    last_q_ = q;
    current_ = true;
  }
  return X_WE_;
}

void ChainKinematics::jacobian(Eigen::Ref<Matrix6Xd> J, JacobianFrame frame) const noexcept {
  const Eigen::Vector3d& p = X_WE_.p;
  for (int i = 0; i < chain_.size(); ++i) {
    if (!on_path_[i]) {
      J.col(i).setZero();
      continue;
    }
    const Eigen::Vector3d& w = axes_[i];
    if (chain_.robot().model().jnt_type[chain_.joint_id(i)] == mjJNT_HINGE) {
      J.col(i).head<3>() = w.cross(p - anchors_[i]);
      J.col(i).tail<3>() = w;
    } else {
      J.col(i).head<3>() = w;
      J.col(i).tail<3>().setZero();
    }
  }
  if (frame == JacobianFrame::local) {
    // column by column: fixed-size temporaries, no heap allocation
    const Eigen::Matrix3d Rt = X_WE_.R.transpose();
    for (int i = 0; i < chain_.size(); ++i) {
      const Eigen::Vector3d v = Rt * J.col(i).head<3>();
      const Eigen::Vector3d w = Rt * J.col(i).tail<3>();
      J.col(i).head<3>() = v;
      J.col(i).tail<3>() = w;
    }
  } else if (frame == JacobianFrame::world) {
    // velocity of the point at the world origin moving with E: v_O = v_E + ω × (0 − p)
    for (int i = 0; i < chain_.size(); ++i) {
      J.col(i).head<3>() += p.cross(Eigen::Vector3d(J.col(i).tail<3>()));
    }
  }
}

Vector6d ChainKinematics::bias_acceleration(const Eigen::Ref<const Eigen::VectorXd>& qd) const noexcept {
  // walk the path: each joint's axis turns with the angular velocity of the joints before it,
  // and the lever arm (p − anchor) stretches with the velocity difference of the two points
  const mjModel& m = chain_.robot().model();
  const Eigen::Vector3d& p = X_WE_.p;
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();  // angular velocity so far
  // frame-point velocity from all joints
  Eigen::Vector3d v_p = Eigen::Vector3d::Zero();
  for (int i : path_order_) {
    const bool hinge = m.jnt_type[chain_.joint_id(i)] == mjJNT_HINGE;
    v_p += (hinge ? axes_[i].cross(p - anchors_[i]) : axes_[i]) * qd[i];
  }
  Vector6d a = Vector6d::Zero();
  for (std::size_t k = 0; k < path_order_.size(); ++k) {
    const int i = path_order_[k];
    const bool hinge = m.jnt_type[chain_.joint_id(i)] == mjJNT_HINGE;
    // velocity of joint i's anchor, caused by the joints before it
    Eigen::Vector3d v_a = Eigen::Vector3d::Zero();
    for (std::size_t l = 0; l < k; ++l) {
      const int j = path_order_[l];
      const bool hinge_j = m.jnt_type[chain_.joint_id(j)] == mjJNT_HINGE;
      v_a += (hinge_j ? axes_[j].cross(anchors_[i] - anchors_[j]) : axes_[j]) * qd[j];
    }
    const Eigen::Vector3d axis_rate = omega.cross(axes_[i]);
    if (hinge) {
      a.head<3>() += (axis_rate.cross(p - anchors_[i]) + axes_[i].cross(v_p - v_a)) * qd[i];
      a.tail<3>() += axis_rate * qd[i];
      omega += axes_[i] * qd[i];
    } else {
      a.head<3>() += axis_rate * qd[i];
    }
  }
  return a;
}

}  // namespace mjarm
