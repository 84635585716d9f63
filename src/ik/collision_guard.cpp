#include "mjarm/ik/collision_guard.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include "mjarm/error.hpp"

namespace mjarm {

CollisionGuard::CollisionGuard(const Chain& chain, const CollisionSpec& spec)
    : chain_(chain), spec_(spec) {
  const Robot& robot = chain_.robot();
  check_fields(spec);
  for (const auto& [a, b] : spec.pairs) {
    const int g1 = robot.geom(a);
    const int g2 = robot.geom(b);
    if (g1 == g2) throw Error("collision pair names geom '" + a + "' twice");
    pair_ids_.emplace_back(g1, g2);
  }
  watched_.assign(robot.model().ngeom, 0);
  for (const std::string& name : spec.geoms) {
    watched_[robot.geom(name)] = 1;
    any_watched_ = true;
  }
  install_mujoco_handlers();
  data_ = robot.make_data();
  const mjModel& m = robot.model();
  fixed_qpos_ = Eigen::Map<const Eigen::VectorXd>(m.qpos0, m.nq);
}

void CollisionGuard::set_fixed_qpos(const Eigen::Ref<const Eigen::VectorXd>& qpos) {
  chain_.check_qpos(qpos, "fixed qpos");
  fixed_qpos_ = qpos;
}

void CollisionGuard::place(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  const mjModel& m = chain_.robot().model();
  std::copy(fixed_qpos_.data(), fixed_qpos_.data() + m.nq, data_->qpos);
  chain_.scatter(q, data_->qpos);
  mj_kinematics(&m, data_.get());
}

double CollisionGuard::pair_distance(int g1, int g2) noexcept {
  const mjModel& m = chain_.robot().model();
  const mjData& d = *data_;
  // bounding spheres first (a plane has rbound 0: no early out)
  const double r1 = m.geom_rbound[g1];
  const double r2 = m.geom_rbound[g2];
  if (r1 > 0.0 && r2 > 0.0) {
    const Eigen::Map<const Eigen::Vector3d> c1(d.geom_xpos + 3 * g1);
    const Eigen::Map<const Eigen::Vector3d> c2(d.geom_xpos + 3 * g2);
    if ((c1 - c2).norm() > r1 + r2 + spec_.margin) return std::numeric_limits<double>::infinity();
  }
  // MuJoCo's narrow phase, capped at the margin (the cap means "no contact within it")
  const double dist = mj_geomDistance(&m, data_.get(), g1, g2, spec_.margin, nullptr);
  return dist < spec_.margin ? dist : std::numeric_limits<double>::infinity();
}

bool CollisionGuard::in_contact(const Eigen::Ref<const Eigen::VectorXd>& q) noexcept {
  place(q);
  for (const auto& [g1, g2] : pair_ids_) {
    if (pair_distance(g1, g2) < spec_.margin) return true;
  }
  if (any_watched_) {
    const mjModel& m = chain_.robot().model();
    mj_collision(&m, data_.get());
    for (int i = 0; i < data_->ncon; ++i) {
      const mjContact& c = data_->contact[i];
      if ((watched_[c.geom1] || watched_[c.geom2]) && c.dist < spec_.margin) return true;
    }
  }
  return false;
}

std::string CollisionGuard::describe_contacts(const Eigen::Ref<const Eigen::VectorXd>& q) {
  const mjModel& m = chain_.robot().model();
  const auto name = [&m](int g) {
    const char* n = mj_id2name(&m, mjOBJ_GEOM, g);
    return n != nullptr ? std::string(n) : "#" + std::to_string(g);
  };
  std::ostringstream out;
  const auto report = [&](int g1, int g2, double dist) {
    if (out.tellp() > 0) out << "; ";
    out << "geom '" << name(g1) << "' – geom '" << name(g2) << "' (distance " << dist << " m)";
  };
  place(q);
  for (const auto& [g1, g2] : pair_ids_) {
    const double dist = pair_distance(g1, g2);
    if (dist < spec_.margin) report(g1, g2, dist);
  }
  if (any_watched_) {
    mj_collision(&m, data_.get());
    for (int i = 0; i < data_->ncon; ++i) {
      const mjContact& c = data_->contact[i];
      if ((watched_[c.geom1] || watched_[c.geom2]) && c.dist < spec_.margin)
        report(c.geom1, c.geom2, c.dist);
    }
  }
  return out.str();
}

}  // namespace mjarm
