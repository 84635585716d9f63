#include "mjarm/sim/step_fault.hpp"

#include <cmath>
#include <cstdio>

namespace mjarm {
namespace {

// warnings after which MuJoCo has reset the data: the run cannot go on
constexpr bool is_fatal(int warning) noexcept {
  return warning == mjWARN_INERTIA || warning == mjWARN_BADQPOS || warning == mjWARN_BADQVEL ||
         warning == mjWARN_BADQACC || warning == mjWARN_BADCTRL;
}

// what lastinfo indexes for each warning
const char* warning_text(int warning) noexcept {
  switch (warning) {
    case mjWARN_INERTIA: return "singular inertia matrix";
    case mjWARN_CONTACTFULL: return "contact buffer full";
    case mjWARN_CNSTRFULL: return "constraint buffer full";
    case mjWARN_BADQPOS: return "bad qpos (MuJoCo)";
    case mjWARN_BADQVEL: return "bad qvel (MuJoCo)";
    case mjWARN_BADQACC: return "bad qacc (MuJoCo)";
    case mjWARN_BADCTRL: return "bad ctrl (MuJoCo)";
    default: return "unknown warning";
  }
}

std::string name_or(const mjModel& m, int type, int id, const char* kind) {
  const char* name = mj_id2name(&m, type, id);
  if (name != nullptr && name[0] != '\0') return std::string("'") + name + "'";
  return std::string(kind) + " " + std::to_string(id);
}

}  // namespace

int joint_of_qpos(const mjModel& m, int qpos_index) noexcept {
  for (int j = m.njnt - 1; j >= 0; --j) {
    if (m.jnt_qposadr[j] <= qpos_index) return j;
  }
  return -1;
}

void DivergenceDetector::rebase(const mjData& d) noexcept {
  for (int w = 0; w < mjNWARNING; ++w) {
    baseline_[w] = d.warning[w].number;
    reported_[w] = false;
  }
}

StepFault DivergenceDetector::check_warnings(const mjModel& m, const mjData& d,
                                             double time) noexcept {
  StepFault fault;
  for (int w = 0; w < mjNWARNING; ++w) {
    if (!is_fatal(w) || d.warning[w].number <= baseline_[w]) continue;
    baseline_[w] = d.warning[w].number;
    fault.cause = FaultCause::mujoco_warning;
    fault.time = time;
    fault.warning = w;
    const int info = d.warning[w].lastinfo;
    if (w == mjWARN_BADQPOS) {
      fault.dof = info;
      fault.joint = joint_of_qpos(m, info);
    } else if (w == mjWARN_BADQVEL || w == mjWARN_BADQACC) {
      fault.dof = info;
      fault.joint = (info >= 0 && info < m.nv) ? m.dof_jntid[info] : -1;
    } else if (w == mjWARN_BADCTRL) {
      fault.actuator = info;
    }
    return fault;
  }
  return fault;
}

StepFault DivergenceDetector::check_state(const mjModel& m, const mjData& d,
                                          double time) const noexcept {
  StepFault fault;
  fault.time = time;
  for (int i = 0; i < m.nq; ++i) {
    if (!std::isfinite(d.qpos[i])) {
      fault.cause = FaultCause::nonfinite_qpos;
      fault.dof = i;
      fault.joint = joint_of_qpos(m, i);
      fault.value = d.qpos[i];
      return fault;
    }
  }
  for (int i = 0; i < m.nv; ++i) {
    const double v = d.qvel[i];
    const double a = d.qacc[i];
    FaultCause cause = FaultCause::none;
    double value = 0.0;
    if (!std::isfinite(v)) {
      cause = FaultCause::nonfinite_qvel;
      value = v;
    } else if (!std::isfinite(a)) {
      cause = FaultCause::nonfinite_qacc;
      value = a;
    } else if (std::abs(a) > max_acceleration_) {
      cause = FaultCause::acceleration_bound;
      value = a;
    }
    if (cause != FaultCause::none) {
      fault.cause = cause;
      fault.dof = i;
      fault.joint = m.dof_jntid[i];
      fault.value = value;
      return fault;
    }
  }
  fault.time = 0.0;
  return fault;
}

int DivergenceDetector::new_benign_warning(const mjData& d) noexcept {
  for (int w = 0; w < mjNWARNING; ++w) {
    if (is_fatal(w) || reported_[w] || d.warning[w].number <= baseline_[w]) continue;
    reported_[w] = true;
    return w;
  }
  return -1;
}

std::string describe(const mjModel& m, const StepFault& fault, const std::string& controller_name) {
  if (fault.ok()) return "no fault";
  char time[48];
  std::snprintf(time, sizeof(time), "t = %.4f s: ", fault.time);
  std::string where;
  if (fault.joint >= 0) {
    const bool qpos = fault.cause == FaultCause::nonfinite_qpos ||
                      (fault.cause == FaultCause::mujoco_warning && fault.warning == mjWARN_BADQPOS);
    where = " at joint " + name_or(m, mjOBJ_JOINT, fault.joint, "joint") + " (" +
            (qpos ? "qpos " : "dof ") + std::to_string(fault.dof) + ")";
  } else if (fault.actuator >= 0) {
    where = " at actuator " + name_or(m, mjOBJ_ACTUATOR, fault.actuator, "actuator");
  }
  char value[64];
  std::snprintf(value, sizeof(value), " (value %g)", fault.value);
  std::string text = time;
  switch (fault.cause) {
    case FaultCause::mujoco_warning:
      text += std::string("MuJoCo warning: ") + warning_text(fault.warning) + where;
      break;
    case FaultCause::nonfinite_qpos: text += "NaN/inf in qpos" + where; break;
    case FaultCause::nonfinite_qvel: text += "NaN/inf in qvel" + where; break;
    case FaultCause::nonfinite_qacc: text += "NaN/inf in qacc" + where; break;
    case FaultCause::acceleration_bound:
      text += "runaway acceleration" + where + value;
      break;
    case FaultCause::bad_command:
      text += "controller '" + controller_name + "' commanded a non-finite value" + where;
      break;
    case FaultCause::none: break;
  }
  if (fault.cause != FaultCause::bad_command) text += "; the simulation diverged";
  return text;
}

}  // namespace mjarm
