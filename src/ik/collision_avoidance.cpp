#include "mjarm/ik/collision_avoidance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

bool is_collision_geom(const mjModel& m, int g) {
  return m.geom_contype[g] != 0 || m.geom_conaffinity[g] != 0;
}

// per body: moved by one of the chain's joints (the joint's body or a descendant)
std::vector<char> moved_bodies(const Chain& chain) {
  const mjModel& m = chain.robot().model();
  std::vector<char> moved(m.nbody, 0);
  for (const int j : chain.joint_ids()) moved[m.jnt_bodyid[j]] = 1;
  // parents precede children in MuJoCo's body order
  for (int b = 1; b < m.nbody; ++b) {
    if (moved[m.body_parentid[b]]) moved[b] = 1;
  }
  return moved;
}

// every collision geom moved by the chain against every collision geom outside the robot's tree
void add_robot_vs_scene(const Chain& chain, std::vector<std::pair<int, int>>& pairs) {
  const mjModel& m = chain.robot().model();
  const std::vector<char> moved = moved_bodies(chain);
  const int robot_root = m.body_rootid[m.jnt_bodyid[chain.joint_id(0)]];
  std::vector<int> robot, scene;
  for (int g = 0; g < m.ngeom; ++g) {
    if (!is_collision_geom(m, g)) continue;
    const int body = m.geom_bodyid[g];
    if (moved[body]) {
      robot.push_back(g);
    } else if (m.body_rootid[body] != robot_root) {
      scene.push_back(g);
    }
  }
  for (const int r : robot) {
    for (const int s : scene) {
      if (std::find(pairs.begin(), pairs.end(), std::pair{r, s}) == pairs.end() &&
          std::find(pairs.begin(), pairs.end(), std::pair{s, r}) == pairs.end()) {
        pairs.emplace_back(r, s);
      }
    }
  }
}

}  // namespace

CollisionAvoidance::CollisionAvoidance(const Chain& chain, const CollisionAvoidanceOptions& options)
    : chain_(chain), options_(options) {
  check_fields(options_);
  if (options_.detection_distance <= options_.min_distance) {
    throw Error("collision avoidance: detection_distance must exceed min_distance (" +
                number_text(options_.min_distance) + " m), got " +
                number_text(options_.detection_distance) + " m");
  }
  const Robot& robot = chain_.robot();
  for (const auto& [a, b] : options_.pairs) {
    const int g1 = robot.geom(a);  // throws naming the closest geom names
    const int g2 = robot.geom(b);
    if (g1 == g2) throw Error("collision avoidance: pair names geom '" + a + "' twice");
    pairs_.emplace_back(g1, g2);
  }
  if (options_.robot_vs_scene) add_robot_vs_scene(chain_, pairs_);
  if (pairs_.empty()) {
    throw Error(options_.robot_vs_scene
                    ? "collision avoidance: robot_vs_scene found no collision geom pair (no "
                      "collision geom moved by the chain, or none outside the robot)"
                    : "collision avoidance: no pair given (set pairs or robot_vs_scene)");
  }
  install_mujoco_handlers();
  data_ = robot.make_data();
  const mjModel& m = robot.model();
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
  jac1_.setZero(3, m.nv);
  jac2_.setZero(3, m.nv);
  jd_.setZero(chain_.size());
  row_pair_.assign(pairs_.size(), 0);
  row_distance_.assign(pairs_.size(), 0.0);
}

void CollisionAvoidance::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
}

void CollisionAvoidance::place(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  const mjModel& m = chain_.robot().model();
  std::copy(fixed_qpos_.data(), fixed_qpos_.data() + m.nq, data_->qpos);
  chain_.scatter(q, data_->qpos);
  mj_kinematics(&m, data_.get());
  mj_comPos(&m, data_.get());  // mj_jac reads cdof and subtree_com
}

double CollisionAvoidance::pair_distance(int g1, int g2, double fromto[6]) noexcept {
  const mjModel& m = chain_.robot().model();
  const mjData& d = *data_;
  const double cap = options_.detection_distance;
  // bounding spheres first (a plane has rbound 0: no early out)
  const double r1 = m.geom_rbound[g1];
  const double r2 = m.geom_rbound[g2];
  if (r1 > 0.0 && r2 > 0.0) {
    const Eigen::Map<const Eigen::Vector3d> c1(d.geom_xpos + 3 * g1);
    const Eigen::Map<const Eigen::Vector3d> c2(d.geom_xpos + 3 * g2);
    if ((c1 - c2).norm() > r1 + r2 + cap) return cap;
  }
  return std::min(mj_geomDistance(&m, data_.get(), g1, g2, cap, fromto), cap);
}

void CollisionAvoidance::distance_jacobian(int g1, int g2, const double fromto[6], double d,
                                           Eigen::VectorXd& row) noexcept {
  const mjModel& m = chain_.robot().model();
  const Eigen::Map<const Eigen::Vector3d> p1(fromto), p2(fromto + 3);
  // MuJoCo writes p₁ = c − (d/2)·n, p₂ = c + (d/2)·n with n its contact normal from geom 1 to
  // geom 2, so p₂ − p₁ = d·n for either sign of d
  Eigen::Vector3d n = p2 - p1;
  const double length = n.norm();
  if (length > 1e-12) {
    n *= (d < 0.0 ? -1.0 : 1.0) / length;
  } else {
    // touching exactly: no segment; the centre-to-centre direction stands in for the normal
    n = Eigen::Map<const Eigen::Vector3d>(data_->geom_xpos + 3 * g2) -
        Eigen::Map<const Eigen::Vector3d>(data_->geom_xpos + 3 * g1);
    const double c = n.norm();
    if (c > 0.0) n /= c;
  }
  mj_jac(&m, data_.get(), jac1_.data(), nullptr, p1.data(), m.geom_bodyid[g1]);
  mj_jac(&m, data_.get(), jac2_.data(), nullptr, p2.data(), m.geom_bodyid[g2]);
  const std::vector<int>& dofs = chain_.dof_addresses();
  for (int i = 0; i < chain_.size(); ++i) {
    row[i] = n.dot(jac2_.col(dofs[i]) - jac1_.col(dofs[i]));
  }
}

double CollisionAvoidance::distance(const Eigen::Ref<const Eigen::VectorXd>& q, int i) noexcept {
  place(q);
  double fromto[6];
  return pair_distance(pairs_[i].first, pairs_[i].second, fromto);
}

int CollisionAvoidance::rows(const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                             Eigen::Ref<Eigen::MatrixXd> C,
                             Eigen::Ref<Eigen::VectorXd> b) noexcept {
  place(q);
  const double cap = options_.detection_distance;
  const double rate = options_.gain / dt;
  min_seen_ = cap;
  int k = 0;
  for (int i = 0; i < pair_count(); ++i) {
    const auto [g1, g2] = pairs_[i];
    double fromto[6];
    const double d = pair_distance(g1, g2, fromto);
    min_seen_ = std::min(min_seen_, d);
    if (!(d < cap)) continue;
    distance_jacobian(g1, g2, fromto, d, jd_);
    C.row(k) = jd_.transpose();
    b[k] = -rate * (d - options_.min_distance);
    row_pair_[k] = i;
    row_distance_[k] = d;
    ++k;
  }
  return k;
}

}  // namespace mjarm
