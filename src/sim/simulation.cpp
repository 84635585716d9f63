#include "mjarm/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"

namespace mjarm {
namespace {

// the options, after checking each declared field against its range
const SimulationOptions& checked(const SimulationOptions& options) {
  check_fields(options);
  return options;
}

// control period as a whole number of physics steps, or a clear error
int steps_per_tick_of(const mjModel& m, double period) {
  const double h = m.opt.timestep;
  if (!(std::isfinite(h) && h > 0.0)) {
    throw Error("simulation: the model's timestep must be positive and finite, got " +
                number_text(h) + " s");
  }
  if (period == 0.0) return 1;
  return whole_multiple(period, h, "simulation: control_period", "the timestep");
}

void check_finite(std::span<const double> values, std::size_t size, const char* what) {
  if (values.size() != size) {
    throw Error(std::string("simulation: ") + what + " needs " + std::to_string(size) +
                " values, got " + std::to_string(values.size()));
  }
  for (std::size_t i = 0; i < size; ++i) {
    if (!std::isfinite(values[i])) {
      throw Error(std::string("simulation: ") + what + "[" + std::to_string(i) + "] is not finite");
    }
  }
}

void check_equality_id(const mjModel& m, int id) {
  if (id < 0 || id >= m.neq) {
    throw Error("simulation: equality id " + std::to_string(id) + " out of range [0, " +
                std::to_string(m.neq) + ")");
  }
}

mjModel* copy_model(const Robot& robot) {
  mjModel* copy = mj_copyModel(nullptr, &robot.model());
  if (copy == nullptr) throw Error("simulation: could not copy model '" + robot.name() + "'");
  return copy;
}

}  // namespace

int whole_multiple(double period, double step, std::string_view what, std::string_view step_name) {
  if (!(std::isfinite(period) && period > 0.0)) {
    throw Error(std::string(what) + " must be positive and finite, got " + number_text(period) +
                " s");
  }
  const double n = std::round(period / step);
  if (n < 1.0 || std::abs(n * step - period) > 1e-9 * period) {
    throw Error(std::string(what) + " " + number_text(period) +
                " s is not a whole multiple of " + std::string(step_name) + " " +
                number_text(step) + " s (nearest: " + number_text(std::max(n, 1.0) * step) +
                " s)");
  }
  return static_cast<int>(n);
}

Simulation::Simulation(const Robot& robot, const SimulationOptions& options)
    : robot_(robot),
      own_model_(options.own_model ? copy_model(robot) : nullptr),
      model_(own_model_ ? own_model_.get() : &robot_.model()),
      options_(options),
      steps_per_tick_(steps_per_tick_of(robot.model(), checked(options).control_period)),
      detector_(options.max_acceleration) {
  if (options.mode == SimulationMode::kinematic && options.contact_check_a.empty() &&
      !options.contact_check_b.empty()) {
    throw Error("simulation: contact_check_b is set but contact_check_a is empty");
  }
  const mjModel& m = model();
  data_ = robot_.make_data();
  commanded_by_.assign(m.nu, -1);
  saturated_.assign(m.nu, 0);
  saturation_counts_.assign(m.nu, 0);
  gravity_added_.assign(m.nv, 0.0);
  if (options.mode == SimulationMode::position && options.gravity_compensation) {
    // every hinge/slide dof driven by a position servo holds itself against its bias forces
    for (const ActuatorInfo& a : robot_.actuators()) {
      if (a.kind != ActuatorKind::position || !a.joint) continue;
      const int type = m.jnt_type[*a.joint];
      if (type != mjJNT_HINGE && type != mjJNT_SLIDE) continue;
      const int dof = m.jnt_dofadr[*a.joint];
      bool seen = false;
      for (int d : gravity_dofs_) seen = seen || d == dof;
      if (!seen) gravity_dofs_.push_back(dof);
    }
  }
  // time, qpos and qvel always lead (Snapshot::qpos, qvel); the other components only if present
  snapshot_.spec = mjSTATE_TIME | mjSTATE_QPOS | mjSTATE_QVEL;
  for (int i = 0; i < mjNSTATE; ++i) {
    const int component = 1 << i;
    if ((mjSTATE_INTEGRATION & component) != 0 && mj_stateSize(&m, component) > 0)
      snapshot_.spec |= component;
  }
  snapshot_.state.resize(static_cast<std::size_t>(mj_stateSize(&m, snapshot_.spec)));
  snapshot_.nq = m.nq;
  after_reset();
}

Simulation::~Simulation() = default;

void Simulation::after_reset() {
  const mjModel& m = model();
  mj_forward(&m, data_.get());
  fault_ = StepFault{};
  detector_.rebase(*data_);
  std::fill(saturated_.begin(), saturated_.end(), 0);
  std::fill(saturation_counts_.begin(), saturation_counts_.end(), 0);
  std::fill(gravity_added_.begin(), gravity_added_.end(), 0.0);
  ticks_ = 0;
  steps_ = 0;
  for (ControllerSlot& slot : controllers_) slot.controller->reset();
  refresh_watches(options_.mode != SimulationMode::kinematic);
}

void Simulation::reset() {
  mj_resetData(&model(), data_.get());
  after_reset();
}

void Simulation::reset(std::string_view keyframe) {
  mj_resetDataKeyframe(&model(), data_.get(), robot_.keyframe(keyframe));
  after_reset();
}

void Simulation::set_state(std::span<const double> qpos, std::span<const double> qvel) {
  const mjModel& m = model();
  check_finite(qpos, m.nq, "qpos");
  check_finite(qvel, m.nv, "qvel");
  std::copy(qpos.begin(), qpos.end(), data_->qpos);
  std::copy(qvel.begin(), qvel.end(), data_->qvel);
  mj_forward(&m, data_.get());
  fault_ = StepFault{};
  detector_.rebase(*data_);
  refresh_watches(options_.mode != SimulationMode::kinematic);
}

void Simulation::restore(const StateSnapshot& snapshot) {
  snapshot.restore(model(), *data_);
  mj_forward(&model(), data_.get());
  fault_ = StepFault{};
  detector_.rebase(*data_);
  refresh_watches(options_.mode != SimulationMode::kinematic);
}

void Simulation::forward() {
  mj_forward(&model(), data_.get());
  refresh_watches(options_.mode != SimulationMode::kinematic);
}

void Simulation::add_controller(Controller& controller) {
  const std::string name(controller.name());
  if (options_.mode == SimulationMode::kinematic) {
    throw Error("simulation: kinematic mode runs no controllers (controller '" + name +
                "'); use position or torque mode");
  }
  const CommandKind wanted =
      options_.mode == SimulationMode::torque ? CommandKind::torque : CommandKind::position;
  if (controller.command_kind() != wanted) {
    throw Error(
        "simulation: " + std::string(to_string(options_.mode)) + " mode takes " +
        (wanted == CommandKind::torque ? "torque" : "position") + " commands, but controller '" +
        name + "' writes " +
        (controller.command_kind() == CommandKind::torque ? "torques" : "position targets"));
  }
  if (options_.mode == SimulationMode::position && options_.gravity_compensation &&
      controller.compensates_bias()) {
    // both would cancel the bias: the servos would settle b / k past their targets
    throw Error("simulation: controller '" + name +
                "' already compensates the bias forces through its servo targets, and this "
                "position-mode simulation adds them too; set SimulationOptions::"
                "gravity_compensation = false to use it");
  }
  if (&controller.chain().robot().model() != &robot_.model()) {
    throw Error("simulation: controller '" + name + "' was built for model '" +
                controller.chain().robot().name() + "', not for this simulation's model '" +
                robot_.name() + "' (load once and share the Robot)");
  }
  auto binding = std::make_unique<ActuatorBinding>(controller.chain(), wanted, name);
  for (int i = 0; i < binding->size(); ++i) {
    const int other = commanded_by_[binding->actuators()[i]];
    if (other >= 0) {
      throw Error("simulation: joint '" + binding->joint_names()[i] +
                  "' is already commanded by controller '" +
                  std::string(controllers_[other].controller->name()) + "'; controller '" + name +
                  "' cannot command it too");
    }
  }
  const int index = static_cast<int>(controllers_.size());
  for (int a : binding->actuators()) commanded_by_[a] = index;
  ControllerSlot slot;
  slot.controller = &controller;
  slot.command.kind = wanted;
  slot.command.value = Eigen::VectorXd::Zero(binding->size());
  slot.binding = std::move(binding);
  controllers_.push_back(std::move(slot));
}

std::string Simulation::describe(const StepFault& fault) const {
  std::string controller_name;
  if (fault.controller >= 0 && fault.controller < controller_count())
    controller_name = std::string(controllers_[fault.controller].controller->name());
  return mjarm::describe(model(), fault, controller_name);
}

std::span<const double> Simulation::sensor(std::string_view name) const {
  return robot_.sensor_values(*data_, name);
}

std::span<const double> Simulation::sensor(int id) const {
  const mjModel& m = model();
  if (id < 0 || id >= m.nsensor) {
    throw Error("simulation: sensor id " + std::to_string(id) + " out of range [0, " +
                std::to_string(m.nsensor) + ")");
  }
  return {data_->sensordata + m.sensor_adr[id], static_cast<std::size_t>(m.sensor_dim[id])};
}

int Simulation::equality(std::string_view name) const {
  return find_object(model(), mjOBJ_EQUALITY, name);
}

bool Simulation::equality_active(int id) const {
  check_equality_id(model(), id);
  return data_->eq_active[id] != 0;
}

bool Simulation::set_equality_active(int id, bool active) noexcept {
  if (id < 0 || id >= model_->neq) return false;
  data_->eq_active[id] = active ? 1 : 0;
  return true;
}

void Simulation::own_model() {
  if (own_model_) return;
  own_model_.reset(copy_model(robot_));
  model_ = own_model_.get();
}

std::span<const double> Simulation::equality_data(int id) const noexcept {
  if (id < 0 || id >= model_->neq) return {};
  return {model_->eq_data + static_cast<std::size_t>(id) * mjNEQDATA, mjNEQDATA};
}

bool Simulation::set_equality_data(int id, std::span<const double> values) noexcept {
  if (!own_model_ || id < 0 || id >= own_model_->neq || values.size() != mjNEQDATA) return false;
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  std::copy(values.begin(), values.end(),
            own_model_->eq_data + static_cast<std::size_t>(id) * mjNEQDATA);
  return true;
}

void Simulation::set_equality_solref(int id, double time_constant, double damping_ratio) {
  check_equality_id(model(), id);
  if (!own_model_) {
    throw Error("simulation: equality solref is model data; call own_model() first (the robot's "
                "model is shared)");
  }
  if (!(std::isfinite(time_constant) && time_constant > 0.0) ||
      !(std::isfinite(damping_ratio) && damping_ratio > 0.0)) {
    throw Error(
        "simulation: equality solref needs a positive time constant [s] and damping "
        "ratio, got " +
        number_text(time_constant) + ", " + number_text(damping_ratio));
  }
  own_model_->eq_solref[id * mjNREF] = time_constant;
  own_model_->eq_solref[id * mjNREF + 1] = damping_ratio;
}

int Simulation::watch_contacts(const GeomSet& a, const GeomSet& b) {
  if (a.empty()) throw Error("simulation: watch_contacts needs a non-empty first geom set");
  watches_.push_back(Watch{a, b, {}});
  refresh_watches(options_.mode != SimulationMode::kinematic);
  return static_cast<int>(watches_.size()) - 1;
}

void Simulation::refresh_watches(bool with_forces) noexcept {
  for (Watch& w : watches_) {
    w.summary = contact_between(model(), *data_, w.a, w.b, with_forces);
  }
}

}  // namespace mjarm
