#include "mjarm/kinematics/contacts.hpp"

namespace mjarm {
namespace {

std::string name_of(const mjModel& m, mjtObj type, int id) {
  const char* name = mj_id2name(&m, type, id);
  return name != nullptr ? name : "";
}

}  // namespace

std::vector<ContactForce> contact_forces(const mjModel& m, const mjData& d) {
  std::vector<ContactForce> out;
  out.reserve(d.ncon);
  for (int c = 0; c < d.ncon; ++c) {
    const mjContact& con = d.contact[c];
    // contacts in the margin gap, fused or without dofs carry no force
    if (con.exclude != 0 || con.efc_address < 0) continue;
    mjtNum f_C[6];
    mj_contactForce(&m, &d, c, f_C);
    // rows of con.frame are the contact axes in world: f_W = frameᵀ · f_C
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> C(con.frame);
    ContactForce f;
    f.geom1 = con.geom1;
    f.geom2 = con.geom2;
    f.body1 = m.geom_bodyid[con.geom1];
    f.body2 = m.geom_bodyid[con.geom2];
    f.geom1_name = name_of(m, mjOBJ_GEOM, f.geom1);
    f.geom2_name = name_of(m, mjOBJ_GEOM, f.geom2);
    f.body1_name = name_of(m, mjOBJ_BODY, f.body1);
    f.body2_name = name_of(m, mjOBJ_BODY, f.body2);
    f.position = Eigen::Map<const Eigen::Vector3d>(con.pos);
    f.normal = C.row(0).transpose();
    f.frame = C;
    f.distance = con.dist;
    f.force_W = C.transpose() * Eigen::Map<const Eigen::Vector3d>(f_C);
    f.normal_force = f_C[0];
    f.friction_W = f.force_W - f.normal_force * f.normal;
    f.torque_W = C.transpose() * Eigen::Map<const Eigen::Vector3d>(f_C + 3);
    out.push_back(f);
  }
  return out;
}

std::vector<BodyPairForce> sum_by_body_pair(const std::vector<ContactForce>& contacts) {
  std::vector<BodyPairForce> pairs;
  for (const ContactForce& c : contacts) {
    // store each pair once with body1 < body2; the force of a flipped contact changes sign
    const bool flip = c.body1 > c.body2;
    const int b1 = flip ? c.body2 : c.body1;
    const int b2 = flip ? c.body1 : c.body2;
    const double sign = flip ? -1.0 : 1.0;
    auto it = pairs.begin();
    while (it != pairs.end() && !(it->body1 == b1 && it->body2 == b2)) ++it;
    if (it == pairs.end()) {
      BodyPairForce pair;
      pair.body1 = b1;
      pair.body2 = b2;
      pairs.push_back(pair);
      it = pairs.end() - 1;
    }
    ++it->contacts;
    it->force_W += sign * c.force_W;
    it->torque_W += sign * c.torque_W;
  }
  return pairs;
}

Eigen::Vector3d contact_force_on_body(const std::vector<ContactForce>& contacts, int body) {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (const ContactForce& c : contacts) {
    if (c.body2 == body) total += c.force_W;
    if (c.body1 == body) total -= c.force_W;
  }
  return total;
}

}  // namespace mjarm
