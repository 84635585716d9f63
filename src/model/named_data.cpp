#include "mjarm/model/named_data.hpp"

#include <array>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {
namespace {

/// How an element's values are found in its array.
enum class Layout {
  qpos,    ///< joint: jnt_qposadr, 7 / 4 / 1 values by joint type
  dof,     ///< joint: jnt_dofadr, 6 / 3 / 1
  rows,    ///< id · width, width values
  act,     ///< actuator: actuator_actadr, actuator_actnum (none: 0 values)
  sensor,  ///< sensor: sensor_adr, sensor_dim
  mocap    ///< body: body_mocapid · width
};

struct Entry {
  NamedQuantity quantity;
  Layout layout;
  int width;  // rows and mocap
  mjtNum* (*array)(mjData&);
};

// clang-format off
constexpr std::array kEntries{
    Entry{{"qpos", mjOBJ_JOINT, true, "joint positions [rad or m]; a free joint: x y z qw qx qy qz"},
          Layout::qpos, 0, [](mjData& d) { return d.qpos; }},
    Entry{{"qvel", mjOBJ_JOINT, true, "joint velocities [rad/s or m/s]; a free joint: v (world), ω (body)"},
          Layout::dof, 0, [](mjData& d) { return d.qvel; }},
    Entry{{"qacc_warmstart", mjOBJ_JOINT, true, "the constraint solver's warm start [rad/s² or m/s²]"},
          Layout::dof, 0, [](mjData& d) { return d.qacc_warmstart; }},
    Entry{{"qfrc_applied", mjOBJ_JOINT, true, "applied generalized forces [N·m or N]"},
          Layout::dof, 0, [](mjData& d) { return d.qfrc_applied; }},
    Entry{{"ctrl", mjOBJ_ACTUATOR, true, "actuator inputs"},
          Layout::rows, 1, [](mjData& d) { return d.ctrl; }},
    Entry{{"act", mjOBJ_ACTUATOR, true, "actuator activations (none for a stateless actuator)"},
          Layout::act, 0, [](mjData& d) { return d.act; }},
    Entry{{"xfrc_applied", mjOBJ_BODY, true, "applied force and torque at the body's centre of mass, world [N, N·m]"},
          Layout::rows, 6, [](mjData& d) { return d.xfrc_applied; }},
    Entry{{"mocap_pos", mjOBJ_BODY, true, "a mocap body's position, world [m]"},
          Layout::mocap, 3, [](mjData& d) { return d.mocap_pos; }},
    Entry{{"mocap_quat", mjOBJ_BODY, true, "a mocap body's orientation, world (w x y z)"},
          Layout::mocap, 4, [](mjData& d) { return d.mocap_quat; }},
    Entry{{"qacc", mjOBJ_JOINT, false, "joint accelerations [rad/s² or m/s²]"},
          Layout::dof, 0, [](mjData& d) { return d.qacc; }},
    Entry{{"qfrc_bias", mjOBJ_JOINT, false, "bias forces C(q, q̇)·q̇ + g(q) [N·m or N]"},
          Layout::dof, 0, [](mjData& d) { return d.qfrc_bias; }},
    Entry{{"qfrc_passive", mjOBJ_JOINT, false, "passive forces: springs, dampers, friction loss [N·m or N]"},
          Layout::dof, 0, [](mjData& d) { return d.qfrc_passive; }},
    Entry{{"qfrc_actuator", mjOBJ_JOINT, false, "actuator forces in joint space [N·m or N]"},
          Layout::dof, 0, [](mjData& d) { return d.qfrc_actuator; }},
    Entry{{"qfrc_constraint", mjOBJ_JOINT, false, "constraint forces: contacts, limits, equalities [N·m or N]"},
          Layout::dof, 0, [](mjData& d) { return d.qfrc_constraint; }},
    Entry{{"actuator_force", mjOBJ_ACTUATOR, false, "actuator forces [N or N·m]"},
          Layout::rows, 1, [](mjData& d) { return d.actuator_force; }},
    Entry{{"actuator_length", mjOBJ_ACTUATOR, false, "actuator lengths [m or rad]"},
          Layout::rows, 1, [](mjData& d) { return d.actuator_length; }},
    Entry{{"actuator_velocity", mjOBJ_ACTUATOR, false, "actuator velocities"},
          Layout::rows, 1, [](mjData& d) { return d.actuator_velocity; }},
    Entry{{"sensordata", mjOBJ_SENSOR, false, "sensor values"},
          Layout::sensor, 0, [](mjData& d) { return d.sensordata; }},
    Entry{{"xpos", mjOBJ_BODY, false, "body frame origin, world [m]"},
          Layout::rows, 3, [](mjData& d) { return d.xpos; }},
    Entry{{"xquat", mjOBJ_BODY, false, "body frame orientation, world (w x y z)"},
          Layout::rows, 4, [](mjData& d) { return d.xquat; }},
    Entry{{"xmat", mjOBJ_BODY, false, "body frame orientation, world (3×3, row-major)"},
          Layout::rows, 9, [](mjData& d) { return d.xmat; }},
    Entry{{"xipos", mjOBJ_BODY, false, "body centre of mass, world [m]"},
          Layout::rows, 3, [](mjData& d) { return d.xipos; }},
    Entry{{"ximat", mjOBJ_BODY, false, "body principal inertia axes, world (3×3, row-major)"},
          Layout::rows, 9, [](mjData& d) { return d.ximat; }},
    Entry{{"cvel", mjOBJ_BODY, false, "body velocity at the subtree centre of mass: ω, v [rad/s, m/s]"},
          Layout::rows, 6, [](mjData& d) { return d.cvel; }},
    Entry{{"cfrc_ext", mjOBJ_BODY, false, "external (contact) wrench on the body at the subtree centre of mass: τ, f"},
          Layout::rows, 6, [](mjData& d) { return d.cfrc_ext; }},
    Entry{{"subtree_com", mjOBJ_BODY, false, "centre of mass of the body's subtree, world [m]"},
          Layout::rows, 3, [](mjData& d) { return d.subtree_com; }},
    Entry{{"site_xpos", mjOBJ_SITE, false, "site position, world [m]"},
          Layout::rows, 3, [](mjData& d) { return d.site_xpos; }},
    Entry{{"site_xmat", mjOBJ_SITE, false, "site orientation, world (3×3, row-major)"},
          Layout::rows, 9, [](mjData& d) { return d.site_xmat; }},
    Entry{{"geom_xpos", mjOBJ_GEOM, false, "geom position, world [m]"},
          Layout::rows, 3, [](mjData& d) { return d.geom_xpos; }},
    Entry{{"geom_xmat", mjOBJ_GEOM, false, "geom orientation, world (3×3, row-major)"},
          Layout::rows, 9, [](mjData& d) { return d.geom_xmat; }},
};
// clang-format on

const Entry* find_entry(std::string_view name) noexcept {
  for (const Entry& e : kEntries)
    if (e.quantity.name == name) return &e;
  return nullptr;
}

const Entry& entry_of(const NamedQuantity& q) {
  if (const Entry* e = find_entry(q.name)) return *e;
  throw Error("named data: unknown quantity '" + std::string(q.name) + "'");
}

int joint_width(const mjModel& m, int joint, bool positions) noexcept {
  switch (m.jnt_type[joint]) {
    case mjJNT_FREE:
      return positions ? 7 : 6;
    case mjJNT_BALL:
      return positions ? 4 : 3;
    default:
      return 1;
  }
}

}  // namespace

std::span<const NamedQuantity> named_quantities() noexcept {
  static const std::array quantities = [] {
    std::array<NamedQuantity, kEntries.size()> out{};
    for (std::size_t i = 0; i < kEntries.size(); ++i) out[i] = kEntries[i].quantity;
    return out;
  }();
  return quantities;
}

const NamedQuantity& named_quantity(std::string_view name) {
  if (const Entry* e = find_entry(name)) return e->quantity;
  std::vector<std::string> known;
  for (const Entry& e : kEntries) known.emplace_back(e.quantity.name);
  throw Error(unknown_name_message("quantity", name, known));
}

int named_count(const mjModel& m, const NamedQuantity& q) noexcept {
  switch (q.element) {
    case mjOBJ_JOINT:
      return m.njnt;
    case mjOBJ_BODY:
      return m.nbody;
    case mjOBJ_SITE:
      return m.nsite;
    case mjOBJ_GEOM:
      return m.ngeom;
    case mjOBJ_ACTUATOR:
      return m.nu;
    case mjOBJ_SENSOR:
      return m.nsensor;
    default:
      return 0;
  }
}

NamedSlice named_slice(const mjModel& m, const NamedQuantity& q, int id) {
  const int count = named_count(m, q);
  if (id < 0 || id >= count) {
    throw Error("named data: " + std::string(q.name) + " has " + std::to_string(count) + " " +
                object_kind_name(q.element) + (count == 1 ? "" : "s") + ", no number " +
                std::to_string(id));
  }
  const Entry& e = entry_of(q);
  switch (e.layout) {
    case Layout::qpos:
      return {m.jnt_qposadr[id], joint_width(m, id, true)};
    case Layout::dof:
      return {m.jnt_dofadr[id], joint_width(m, id, false)};
    case Layout::rows:
      return {id * e.width, e.width};
    case Layout::act:
      return m.actuator_actadr[id] < 0 ? NamedSlice{0, 0}
                                       : NamedSlice{m.actuator_actadr[id], m.actuator_actnum[id]};
    case Layout::sensor:
      return {m.sensor_adr[id], m.sensor_dim[id]};
    case Layout::mocap: {
      const int mocap = m.body_mocapid[id];
      if (mocap < 0) {
        const char* name = mj_id2name(&m, mjOBJ_BODY, id);
        throw Error("named data: body '" + std::string(name ? name : std::to_string(id)) +
                    "' is not a mocap body (" + std::string(q.name) + ")");
      }
      return {mocap * e.width, e.width};
    }
  }
  return {};
}

std::span<mjtNum> named_array(const mjModel& m, mjData& d, const NamedQuantity& q) noexcept {
  const Entry* found = find_entry(q.name);
  if (found == nullptr) return {};
  std::size_t size = 0;
  switch (found->layout) {
    case Layout::qpos:
      size = static_cast<std::size_t>(m.nq);
      break;
    case Layout::dof:
      size = static_cast<std::size_t>(m.nv);
      break;
    case Layout::rows:
      size = static_cast<std::size_t>(named_count(m, q)) * static_cast<std::size_t>(found->width);
      break;
    case Layout::act:
      size = static_cast<std::size_t>(m.na);
      break;
    case Layout::sensor:
      size = static_cast<std::size_t>(m.nsensordata);
      break;
    case Layout::mocap:
      size = static_cast<std::size_t>(m.nmocap) * static_cast<std::size_t>(found->width);
      break;
  }
  return {found->array(d), size};
}

int NamedData::id(const NamedQuantity& q, std::string_view element) const {
  return find_object(*model_, q.element, element);
}

std::vector<std::string> NamedData::names(const NamedQuantity& q) const {
  return object_names(*model_, q.element);
}

Eigen::Map<Eigen::VectorXd> NamedData::operator()(std::string_view quantity,
                                                  std::string_view element) const {
  const NamedQuantity& q = named_quantity(quantity);
  return values(q, id(q, element));
}

Eigen::Map<Eigen::VectorXd> NamedData::operator()(std::string_view quantity, int id) const {
  return values(named_quantity(quantity), id);
}

Eigen::Map<Eigen::VectorXd> NamedData::values(const NamedQuantity& q, int id) const {
  const NamedSlice slice = named_slice(*model_, q, id);
  return {named_array(*model_, *data_, q).data() + slice.offset, slice.size};
}

}  // namespace mjarm
