#include "mjarm/sim/contact_query.hpp"

#include <algorithm>

namespace mjarm {
namespace {

void add_body(const mjModel& m, int body, bool subtree, std::vector<std::uint8_t>& mask) {
  for (int g = 0; g < m.ngeom; ++g) {
    int b = m.geom_bodyid[g];
    if (b == body) {
      mask[g] = 1;
      continue;
    }
    if (!subtree) continue;
    // walk up to the world: body 0 is everybody's ancestor, so the world's subtree is every geom
    while (b != 0 && b != body) b = m.body_parentid[b];
    if (b == body) mask[g] = 1;
  }
}

}  // namespace

GeomSet GeomSet::of_bodies(const Robot& robot, const std::vector<std::string>& bodies,
                           bool subtree) {
  const mjModel& m = robot.model();
  GeomSet set;
  set.mask_.assign(m.ngeom, 0);
  for (const std::string& name : bodies) add_body(m, robot.body(name), subtree, set.mask_);
  return set;
}

GeomSet GeomSet::of_geoms(const Robot& robot, const std::vector<std::string>& geoms) {
  GeomSet set;
  set.mask_.assign(robot.model().ngeom, 0);
  for (const std::string& name : geoms) set.mask_[robot.geom(name)] = 1;
  return set;
}

GeomSet GeomSet::complement(const Robot& robot) const {
  GeomSet set;
  set.mask_.assign(robot.model().ngeom, 1);
  for (std::size_t g = 0; g < mask_.size() && g < set.mask_.size(); ++g) set.mask_[g] = !mask_[g];
  return set;
}

GeomSet& GeomSet::add(const GeomSet& other) {
  if (mask_.size() < other.mask_.size()) mask_.resize(other.mask_.size(), 0);
  for (std::size_t g = 0; g < other.mask_.size(); ++g) mask_[g] |= other.mask_[g];
  return *this;
}

int GeomSet::size() const noexcept {
  return static_cast<int>(std::count(mask_.begin(), mask_.end(), std::uint8_t{1}));
}

ContactSummary contact_between(const mjModel& m, const mjData& d, const GeomSet& a,
                               const GeomSet& b, bool with_forces) noexcept {
  ContactSummary summary;
  summary.forces_valid = with_forces;
  if (a.empty()) return summary;
  const bool b_is_rest = b.empty();
  for (int c = 0; c < d.ncon; ++c) {
    const mjContact& con = d.contact[c];
    if (con.exclude != 0) continue;
    const bool in_b1 = b_is_rest ? !a.contains(con.geom1) : b.contains(con.geom1);
    const bool in_b2 = b_is_rest ? !a.contains(con.geom2) : b.contains(con.geom2);
    // the force MuJoCo reports is geom1 on geom2: A on B when geom1 ∈ A, minus that otherwise
    double sign = 0.0;
    if (a.contains(con.geom1) && in_b2) {
      sign = 1.0;
    } else if (a.contains(con.geom2) && in_b1) {
      sign = -1.0;
    } else {
      continue;
    }
    if (summary.contacts == 0) {
      summary.first_geom_a = sign > 0 ? con.geom1 : con.geom2;
      summary.first_geom_b = sign > 0 ? con.geom2 : con.geom1;
    }
    ++summary.contacts;
    summary.min_distance = std::min(summary.min_distance, static_cast<double>(con.dist));
    if (!with_forces || con.efc_address < 0) continue;
    mjtNum f_C[6];
    mj_contactForce(&m, &d, c, f_C);
    // rows of con.frame are the contact axes in world: f_W = frameᵀ · f_C
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> C(con.frame);
    summary.force_W += sign * (C.transpose() * Eigen::Map<const Eigen::Vector3d>(f_C));
    summary.normal_force += f_C[0];
  }
  return summary;
}

}  // namespace mjarm
