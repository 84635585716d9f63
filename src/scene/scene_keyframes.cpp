#include "scene_keyframes.hpp"

#include <algorithm>
#include <cstddef>

#include "mjarm/error.hpp"

namespace mjarm::scene_detail {

namespace {

// qpos entries of a joint
int joint_coordinates(const mjModel& m, int joint) {
  switch (m.jnt_type[joint]) {
    case mjJNT_FREE:
      return 7;
    case mjJNT_BALL:
      return 4;
    default:
      return 1;
  }
}

}  // namespace

std::pair<SpecPtr, Robot> compile_combining_keys(const mjSpec& spec, const std::string& scene_name,
                                                 const std::vector<std::string>& warnings,
                                                 const std::vector<PartKeys>& keyed) {
  SpecPtr copy(mj_copySpec(&spec));
  if (!copy) throw Error("scene '" + scene_name + "': MuJoCo could not copy the scene's spec");
  const std::string what = "scene '" + scene_name + "'";
  Robot robot = Robot::from_spec(*copy, what, warnings);
  if (keyed.empty()) return {std::move(copy), std::move(robot)};
  // the parts' keys, assembled in the scene's layout by the first compilation, become one
  // key per name: each part's values at its own joints and actuators, qpos0 and 0 elsewhere
  const mjModel& m = robot.model();
  std::vector<std::string> combined;
  for (const PartKeys& part : keyed)
    for (const std::string& key : part.keys)
      if (std::find(combined.begin(), combined.end(), key) == combined.end())
        combined.push_back(key);
  for (const std::string& key : combined) {
    std::vector<double> qpos(m.qpos0, m.qpos0 + m.nq);
    std::vector<double> ctrl(static_cast<std::size_t>(m.nu), 0.0);
    for (const PartKeys& part : keyed) {
      if (std::find(part.keys.begin(), part.keys.end(), key) == part.keys.end()) continue;
      const int k = mj_name2id(&m, mjOBJ_KEY, (part.prefix + key).c_str());
      if (k < 0) continue;
      for (const std::string& joint : part.joints) {
        const int j = mj_name2id(&m, mjOBJ_JOINT, joint.c_str());
        if (j < 0) continue;
        const int adr = m.jnt_qposadr[j];
        const double* from = m.key_qpos + static_cast<std::ptrdiff_t>(k) * m.nq + adr;
        std::copy(from, from + joint_coordinates(m, j), qpos.begin() + adr);
      }
      for (const std::string& actuator : part.actuators) {
        const int a = mj_name2id(&m, mjOBJ_ACTUATOR, actuator.c_str());
        if (a >= 0) ctrl[static_cast<std::size_t>(a)] = m.key_ctrl[k * m.nu + a];
      }
    }
    mjsKey* spec_key = mjs_addKey(copy.get());
    mjs_setName(spec_key->element, key.c_str());
    mjs_setDouble(spec_key->qpos, qpos.data(), m.nq);
    if (m.nu > 0) mjs_setDouble(spec_key->ctrl, ctrl.data(), m.nu);
  }
  for (const PartKeys& part : keyed) {
    for (const std::string& key : part.keys) {
      const std::string name = part.prefix + key;
      if (mjsElement* e = mjs_findElement(copy.get(), mjOBJ_KEY, name.c_str()))
        mjs_delete(copy.get(), e);
    }
  }
  Robot combined_robot = Robot::from_spec(*copy, what, warnings);
  return {std::move(copy), std::move(combined_robot)};
}

}  // namespace mjarm::scene_detail
