#include "mjarm/planning/robot_contacts.hpp"

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"

namespace mjarm {

namespace {

/// Per geom: 1 when its body is moved by a joint of @p chain (the joint's body or below it).
std::vector<char> geoms_moved_by(const Chain& chain) {
  const mjModel& m = chain.robot().model();
  std::vector<char> moved_body(m.nbody, 0);
  for (int id : chain.joint_ids()) moved_body[m.jnt_bodyid[id]] = 1;
  // bodies come after their parents: one pass spreads the flag down the tree
  for (int b = 1; b < m.nbody; ++b)
    if (moved_body[m.body_parentid[b]]) moved_body[b] = 1;
  std::vector<char> moving(m.ngeom, 0);
  for (int g = 0; g < m.ngeom; ++g) moving[g] = moved_body[m.geom_bodyid[g]];
  return moving;
}

/// The geoms a name stands for: the geom of that name and every geom of the body of that name
/// (models often name a link's body and its main geom alike).
std::vector<int> geoms_named(const mjModel& m, std::string_view name) {
  const std::string text(name);
  const int geom = mj_name2id(&m, mjOBJ_GEOM, text.c_str());
  const int body = mj_name2id(&m, mjOBJ_BODY, text.c_str());
  if (geom < 0 && body < 0) {
    std::vector<std::string> known;
    for (int g = 0; g < m.ngeom; ++g)
      if (const char* n = mj_id2name(&m, mjOBJ_GEOM, g); n != nullptr && *n != '\0')
        known.emplace_back(n);
    for (int b = 0; b < m.nbody; ++b)
      if (const char* n = mj_id2name(&m, mjOBJ_BODY, b); n != nullptr && *n != '\0')
        known.emplace_back(n);
    throw Error("allowed collision: " + unknown_name_message("geom or body", name, known));
  }
  std::vector<int> geoms;
  for (int g = 0; g < m.ngeom; ++g)
    if (g == geom || (body >= 0 && m.geom_bodyid[g] == body)) geoms.push_back(g);
  return geoms;
}

}  // namespace

RobotContacts::RobotContacts(const Chain& chain)
    : robot_(chain.robot()),
      ngeom_(robot_.model().ngeom),
      moving_(geoms_moved_by(chain)),
      allowed_(static_cast<std::size_t>(ngeom_) * ngeom_, 0) {}

void RobotContacts::allow(int geom1, int geom2) {
  if (geom1 < 0 || geom2 < 0 || geom1 >= ngeom_ || geom2 >= ngeom_) return;
  allowed_[static_cast<std::size_t>(geom1) * ngeom_ + geom2] = 1;
  allowed_[static_cast<std::size_t>(geom2) * ngeom_ + geom1] = 1;
}

void RobotContacts::allow(std::string_view first, std::string_view second) {
  const std::vector<int> a = geoms_named(robot_.model(), first);
  const std::vector<int> b = geoms_named(robot_.model(), second);
  for (int g1 : a)
    for (int g2 : b) allow(g1, g2);
}

bool RobotContacts::counts(int geom1, int geom2) const noexcept {
  return (moving_[geom1] != 0 || moving_[geom2] != 0) &&
         allowed_[static_cast<std::size_t>(geom1) * ngeom_ + geom2] == 0;
}

RobotContact RobotContacts::deepest(const mjData& d, double margin) const noexcept {
  RobotContact deepest;
  for (int c = 0; c < d.ncon; ++c) {
    const mjContact& contact = d.contact[c];
    if (!(contact.dist < margin) || !(contact.dist < deepest.distance) ||
        !counts(contact.geom1, contact.geom2))
      continue;
    const bool first_moves = moving_[contact.geom1] != 0;
    deepest.distance = contact.dist;
    deepest.geom1 = first_moves ? contact.geom1 : contact.geom2;
    deepest.geom2 = first_moves ? contact.geom2 : contact.geom1;
  }
  return deepest;
}

std::string RobotContacts::geom_name(int g) const {
  const char* name = mj_id2name(&robot_.model(), mjOBJ_GEOM, g);
  return name != nullptr ? "geom '" + std::string(name) + "'" : "geom #" + std::to_string(g);
}

}  // namespace mjarm
