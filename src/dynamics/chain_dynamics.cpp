#include "mjarm/dynamics/chain_dynamics.hpp"

#include <algorithm>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Eigen::Map<const Eigen::Vector3d> vec3(const double* p) { return Eigen::Map<const Eigen::Vector3d>(p); }

// true when body a is b or one of b's ancestors
bool is_ancestor_or_self(const mjModel& m, int a, int b) {
  for (int body = b; body > 0; body = m.body_parentid[body]) {
    if (body == a) return true;
  }
  return a == 0;
}

}  // namespace

ChainDynamics::ChainDynamics(const Chain& chain) : chain_(chain) {
  const mjModel& m = chain_.robot().model();
  const int n = chain_.size();
  for (int i = 0; i < n; ++i) {
    const int type = m.jnt_type[chain_.joint_id(i)];
    if (type != mjJNT_HINGE && type != mjJNT_SLIDE) {
      throw Error("ChainDynamics: joint '" + chain_.joint_names()[i] + "' is not a hinge or a slide");
    }
  }
  frame_body_ = chain_.frame().kind == FrameKind::site ? m.site_bodyid[chain_.frame().id] : chain_.frame().id;
  root_body_ = m.body_rootid[frame_body_];

  // the chain block of MuJoCo's sparse M (the lower triangle by rows, compressed: a dof's row
  // holds its ancestors and itself); an entry whose column is also a chain dof lands in the block
  std::vector<int> chain_index(static_cast<std::size_t>(m.nv), -1);
  for (int i = 0; i < n; ++i) chain_index[static_cast<std::size_t>(chain_.dof_address(i))] = i;
  for (int r = 0; r < n; ++r) {
    const int row = chain_.dof_address(r);
    for (int k = m.M_rowadr[row]; k < m.M_rowadr[row] + m.M_rownnz[row]; ++k) {
      const int c = chain_index[static_cast<std::size_t>(m.M_colind[k])];
      if (c >= 0) mass_entries_.push_back({r, c, k});
    }
  }

  // every dof on the path from the world to E's body, root first
  for (int body = frame_body_; body > 0; body = m.body_parentid[body]) {
    for (int k = m.body_dofnum[body] - 1; k >= 0; --k) path_dofs_.push_back(m.body_dofadr[body] + k);
  }
  std::reverse(path_dofs_.begin(), path_dofs_.end());

  for (int i = 0; i < n; ++i) {
    const int body = m.jnt_bodyid[chain_.joint_id(i)];
    joint_body_.push_back(body);
    subtree_mass_.push_back(m.body_subtreemass[body]);
    chain_on_path_.push_back(is_ancestor_or_self(m, body, frame_body_) ? 1 : 0);
  }

  q_ = Eigen::VectorXd::Zero(n);
  qd_ = Eigen::VectorXd::Zero(n);
  M_ = Eigen::MatrixXd::Zero(n, n);
  h_ = Eigen::VectorXd::Zero(n);
  g_ = Eigen::VectorXd::Zero(n);
  J_ = Matrix6Xd::Zero(6, n);
  qacc_full_ = Eigen::VectorXd::Zero(m.nv);
  force_full_ = Eigen::VectorXd::Zero(m.nv);
}

void ChainDynamics::update(const mjData& d) noexcept {
  const mjModel& m = chain_.robot().model();
  const int n = chain_.size();

  // state, mass matrix block, bias forces
  for (int i = 0; i < n; ++i) {
    q_[i] = d.qpos[chain_.qpos_address(i)];
    qd_[i] = d.qvel[chain_.dof_address(i)];
    h_[i] = d.qfrc_bias[chain_.dof_address(i)];
  }
  for (const MassEntry& e : mass_entries_) {
    M_(e.row, e.col) = d.M[e.address];
    M_(e.col, e.row) = d.M[e.address];
  }

  // frame pose
  const bool site = chain_.frame().kind == FrameKind::site;
  const int id = chain_.frame().id;
  X_WE_.p = vec3(site ? d.site_xpos + 3 * id : d.xpos + 3 * id);
  X_WE_.R = Eigen::Map<const RowMajor3>(site ? d.site_xmat + 9 * id : d.xmat + 9 * id);
  const Eigen::Vector3d& p = X_WE_.p;

  // Jacobian from the joint axes and anchors; gravity torques from subtree masses and centres
  const bool gravity_on = (m.opt.disableflags & mjDSBL_GRAVITY) == 0;
  const Eigen::Vector3d gravity = gravity_on ? Eigen::Vector3d(vec3(m.opt.gravity)) : Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const int joint = chain_.joint_id(i);
    const Eigen::Vector3d axis = vec3(d.xaxis + 3 * joint);
    const Eigen::Vector3d anchor = vec3(d.xanchor + 3 * joint);
    const bool hinge = m.jnt_type[joint] == mjJNT_HINGE;
    const Eigen::Vector3d com = vec3(d.subtree_com + 3 * joint_body_[i]);
    const double mass = subtree_mass_[i];
    g_[i] = hinge ? -mass * gravity.dot(axis.cross(com - anchor)) : -mass * gravity.dot(axis);
    if (!chain_on_path_[i]) {
      J_.col(i).setZero();
    } else if (hinge) {
      J_.col(i) << axis.cross(p - anchor), axis;
    } else {
      J_.col(i) << axis, Eigen::Vector3d::Zero();
    }
  }

  // E's velocity and bias acceleration from MuJoCo's com-based quantities: spatial vectors are
  // [ω; v] at the subtree com of the root body c. With zero accelerations the body's spatial
  // acceleration is Σ cdof_dot·q̇ over its ancestor dofs (as in mj_rne without gravity); moving
  // it to E's origin and adding ω × v gives the classical acceleration of that point.
  const Eigen::Vector3d offset = p - vec3(d.subtree_com + 3 * root_body_);
  const Eigen::Vector3d omega = vec3(d.cvel + 6 * frame_body_);
  const Eigen::Vector3d v = vec3(d.cvel + 6 * frame_body_ + 3) + omega.cross(offset);
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int dof : path_dofs_) {
    const double rate = d.qvel[dof];
    alpha += rate * vec3(d.cdof_dot + 6 * dof);
    a += rate * vec3(d.cdof_dot + 6 * dof + 3);
  }
  V_WE_ << v, omega;
  Jdot_qd_ << a + alpha.cross(offset) + omega.cross(v), alpha;
}

void ChainDynamics::inverse_dynamics(const mjData& d, const Eigen::Ref<const Eigen::VectorXd>& qdd,
                                     Eigen::Ref<Eigen::VectorXd> tau) noexcept {
  const mjModel& m = chain_.robot().model();
  const int n = chain_.size();
  qacc_full_.setZero();
  for (int i = 0; i < n; ++i) qacc_full_[chain_.dof_address(i)] = qdd[i];
  // sparse M·q̈ on the whole tree (reads M only), then the chain's rows plus qfrc_bias
  mj_mulM(&m, &d, force_full_.data(), qacc_full_.data());
  for (int i = 0; i < n; ++i) {
    const int dof = chain_.dof_address(i);
    tau[i] = force_full_[dof] + d.qfrc_bias[dof];
  }
}

}  // namespace mjarm
