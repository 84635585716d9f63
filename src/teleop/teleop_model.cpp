#include "teleop_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "mjarm/error.hpp"

namespace mjarm::detail {

namespace {

constexpr const char* kTorqueSuffix = "_torque";

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::optional<Robot> model_variant(const Robot& robot, bool torque) {
  const std::filesystem::path source = robot.source();
  if (source.empty() || robot.source() == "<string>") return std::nullopt;
  const std::string stem = source.stem().string();
  if (ends_with(stem, kTorqueSuffix) == torque) return robot;  // already that flavour
  const std::string other = torque
                                ? stem + kTorqueSuffix
                                : stem.substr(0, stem.size() - std::string(kTorqueSuffix).size());
  const std::filesystem::path path = source.parent_path() / (other + source.extension().string());
  if (!std::filesystem::exists(path)) return std::nullopt;
  return Robot::from_file(path);
}

std::string model_variant_missing(const Robot& robot, bool torque) {
  const std::filesystem::path source = robot.source();
  const std::string stem = source.stem().string();
  return std::string(torque ? "torque" : "position") + " mode needs the model's " +
         (torque ? "torque-motor variant '" + stem + kTorqueSuffix + source.extension().string()
                 : "position-servo variant") +
         "' beside '" + robot.source() + "'";
}

std::vector<std::string> gripper_joints(const Chain& arm) {
  const mjModel& m = arm.robot().model();
  const int last_body = m.jnt_bodyid[arm.joint_ids().back()];
  std::vector<std::string> names;
  for (int j = 0; j < m.njnt; ++j) {
    const auto& ids = arm.joint_ids();
    if (std::find(ids.begin(), ids.end(), j) != ids.end()) continue;
    if ((m.jnt_type[j] != mjJNT_HINGE && m.jnt_type[j] != mjJNT_SLIDE) || !m.jnt_limited[j])
      continue;
    int b = m.jnt_bodyid[j];
    while (b > 0 && b != last_body) b = m.body_parentid[b];
    const char* name = mj_id2name(&m, mjOBJ_JOINT, j);
    if (b == last_body && name != nullptr) names.emplace_back(name);
  }
  return names;
}

void build_mode_rigs(const Robot& robot, std::array<std::string, 3>& reasons,
                     const std::function<void(const Robot&, SimulationMode)>& build) {
  for (int m = 0; m < 3; ++m) {
    const auto mode = static_cast<SimulationMode>(m);
    const bool torque = mode == SimulationMode::torque;
    try {
      std::optional<Robot> model = robot;
      if (mode != SimulationMode::kinematic) model = model_variant(robot, torque);
      if (!model) {
        reasons[m] = model_variant_missing(robot, torque);
        continue;
      }
      build(*model, mode);
    } catch (const Error& e) {
      if (mode == SimulationMode::kinematic) throw;  // the frame itself is wrong
      reasons[m] = std::string(to_string(mode)) + " mode unavailable: " + e.what();
    }
  }
}

std::string initial_keyframe(const Robot& robot, const std::string& keyframe) {
  if (!keyframe.empty()) {
    robot.keyframe(keyframe);  // throws for an unknown name, listing close ones
    return keyframe;
  }
  const auto keys = robot.keyframe_names();
  return std::find(keys.begin(), keys.end(), "home") != keys.end() ? "home" : "";
}

Pose read_frame(const mjData& d, const FrameRef& frame) noexcept {
  const bool site = frame.kind == FrameKind::site;
  const double* p = site ? d.site_xpos + 3 * frame.id : d.xpos + 3 * frame.id;
  const double* R = site ? d.site_xmat + 9 * frame.id : d.xmat + 9 * frame.id;
  Pose X;
  X.p = Eigen::Vector3d(p[0], p[1], p[2]);
  X.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(R);
  return X;
}

std::unique_ptr<Simulation> rig_simulation(const Robot& robot, SimulationMode mode,
                                           double kinematic_period, double control_period,
                                           const GeomSet& contact_check, double& period) {
  SimulationOptions options;
  options.mode = mode;
  const double h = robot.model().opt.timestep;
  if (mode == SimulationMode::kinematic) {
    period = h * std::max(1.0, std::round(kinematic_period / h));
    options.contact_check_a = contact_check;
  } else {
    options.control_period = control_period;
  }
  auto sim = std::make_unique<Simulation>(robot, options);
  if (mode != SimulationMode::kinematic) period = sim->control_period();
  return sim;
}

void reset_simulation(Simulation& sim, const std::string& keyframe) {
  const auto keys = sim.robot().keyframe_names();
  if (!keyframe.empty() && std::find(keys.begin(), keys.end(), keyframe) != keys.end()) {
    sim.reset(keyframe);
  } else {
    sim.reset();
  }
}

void carry_state(const Simulation& from, Simulation& to) {
  const mjModel& mf = from.model();
  const mjModel& mt = to.model();
  if (mf.nq == mt.nq && mf.nv == mt.nv) {
    const mjData& d = from.data();
    const std::vector<double> qvel(d.qvel, d.qvel + mt.nv);
    to.set_state(std::span<const double>(d.qpos, static_cast<std::size_t>(mt.nq)), qvel);
    to.data().time = d.time;  // the clock goes on across the switch
  } else {
    to.reset();
  }
  for (int c = 0; c < to.controller_count(); ++c) to.controller(c).reset();
}

std::string root_body(const mjModel& m, int joint) {
  int b = m.jnt_bodyid[joint];
  while (b > 0 && m.body_parentid[b] > 0) b = m.body_parentid[b];
  const char* name = mj_id2name(&m, mjOBJ_BODY, b);
  return name != nullptr ? name : "";
}

}  // namespace mjarm::detail
