#include "mjarm/sim/weld_grasp.hpp"

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {
namespace {

int checked_weld(const Simulation& simulation, int id) {
  const mjModel& m = simulation.model();
  if (m.eq_type[id] != mjEQ_WELD) {
    const char* name = mj_id2name(&m, mjOBJ_EQUALITY, id);
    throw Error("weld grasp: equality '" + std::string(name ? name : "?") +
                "' is not a weld (a weld equality between the gripper and the object is needed)");
  }
  return id;
}

Pose body_pose(const mjData& d, int body) noexcept {
  Pose X;
  X.p = Eigen::Map<const Eigen::Vector3d>(d.xpos + 3 * body);
  X.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.xmat + 9 * body);
  return X;
}

}  // namespace

WeldGrasp::WeldGrasp(Simulation& simulation, std::string_view weld, const WeldGraspOptions& options)
    : WeldGrasp(simulation, simulation.equality(weld), options) {}

WeldGrasp::WeldGrasp(Simulation& simulation, int id, const WeldGraspOptions& options)
    : simulation_(&simulation), id_(checked_weld(simulation, id)), options_(options) {
  const mjModel& m = simulation.model();
  body1_ = m.eq_obj1id[id_];
  body2_ = m.eq_obj2id[id_];
  const char* name = mj_id2name(&m, mjOBJ_EQUALITY, id_);
  name_ = name ? name : "";
  // the relative pose and the solver reference are model data: this simulation's own
  simulation.own_model();
  simulation.set_equality_solref(id_, options.time_constant, options.damping_ratio);
  simulation.set_equality_active(id_, false);
}

WeldGrasp WeldGrasp::between(Simulation& simulation, std::string_view gripper,
                             std::string_view object, const WeldGraspOptions& options) {
  const mjModel& m = simulation.model();
  const int a = find_object(m, mjOBJ_BODY, gripper);
  const int b = find_object(m, mjOBJ_BODY, object);
  for (int e = 0; e < m.neq; ++e) {
    if (m.eq_type[e] != mjEQ_WELD) continue;
    if (m.eq_obj1id[e] == a && m.eq_obj2id[e] == b) return WeldGrasp(simulation, e, options);
    if (m.eq_obj1id[e] == b && m.eq_obj2id[e] == a) return WeldGrasp(simulation, e, options);
  }
  throw Error("weld grasp: model '" + simulation.robot().name() + "' has no weld between body '" +
              std::string(gripper) + "' and body '" + std::string(object) +
              "' (add one: Scene::add_weld, or a <weld> in the MJCF)");
}

bool WeldGrasp::activate() noexcept {
  const mjData& d = simulation_->data();
  const Pose X_W1 = body_pose(d, body1_);
  const Pose X_W2 = body_pose(d, body2_);
  // the relative orientation from MuJoCo's own quaternions: q_12 = q_1⁻¹ ⊗ q_2
  mjtNum q1_inverse[4], q12[4];
  mju_negQuat(q1_inverse, d.xquat + 4 * body1_);
  mju_mulQuat(q12, q1_inverse, d.xquat + 4 * body2_);
  mju_normalize4(q12);
  const Eigen::Vector3d p_12 = X_W1.R.transpose() * (X_W2.p - X_W1.p);
  const std::span<const double> old = simulation_->equality_data(id_);
  std::array<double, mjNEQDATA> data{};
  for (int i = 0; i < mjNEQDATA; ++i) data[i] = old[i];
  data[0] = data[1] = data[2] = 0.0;  // anchor: body2's origin
  for (int i = 0; i < 3; ++i) data[3 + i] = p_12[i];
  for (int i = 0; i < 4; ++i) data[6 + i] = q12[i];
  data[11] = 0.0;  // the pose is ours now: mj_setConst (domain randomization) must keep it
  if (!simulation_->set_equality_data(id_, data)) return false;
  X_12_.p = p_12;
  X_12_.R = X_W1.R.transpose() * X_W2.R;
  activated_once_ = true;
  return simulation_->set_equality_active(id_, true);
}

void WeldGrasp::release() noexcept { simulation_->set_equality_active(id_, false); }

bool WeldGrasp::active() const noexcept { return simulation_->data().eq_active[id_] != 0; }

double WeldGrasp::deviation() const noexcept {
  if (!activated_once_) return 0.0;
  const mjData& d = simulation_->data();
  const Pose X_W1 = body_pose(d, body1_);
  const Eigen::Vector3d held = X_W1.act(X_12_.p);
  return (Eigen::Map<const Eigen::Vector3d>(d.xpos + 3 * body2_) - held).norm();
}

}  // namespace mjarm
