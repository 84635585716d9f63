// The stepping half of Simulation: control ticks, runs and kinematic moves.
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm {
namespace {

bool all_finite(std::span<const double> v) noexcept {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4f s", t);
  return text;
}

const char* warning_name(int warning) noexcept {
  switch (warning) {
    case mjWARN_CONTACTFULL: return "MuJoCo warning: contact buffer full (contacts dropped)";
    case mjWARN_CNSTRFULL: return "MuJoCo warning: constraint buffer full (constraints dropped)";
    default: return "MuJoCo warning";
  }
}

}  // namespace

TickResult Simulation::tick(const Reference& reference, Recorder* recorder) {
  return tick_impl(nullptr, &reference, recorder);
}

TickResult Simulation::tick(ReferenceSource& source, Recorder* recorder) {
  return tick_impl(&source, nullptr, recorder);
}

TickResult Simulation::tick_impl(ReferenceSource* source, const Reference* reference,
                                 Recorder* recorder) {
  if (options_.mode == SimulationMode::kinematic) {
    throw Error("simulation: tick() needs position or torque mode; kinematic mode moves with move()");
  }
  const mjModel& m = model();
  mjData* d = data_.get();
  TickResult result;
  if (!fault_.ok()) {  // a fault stops the simulation until reset or set_state
    result.status =
        fault_.cause == FaultCause::bad_command ? TickStatus::bad_command : TickStatus::diverged;
    result.fault = fault_;
    result.time = d->time;
    return result;
  }
  const bool rk4 = uses_rk4();
  const bool compensate = !gravity_dofs_.empty();
  for (int s = 0; s < steps_per_tick_; ++s) {
    take_snapshot();
    const double t0 = d->time;
    // fresh positions, velocities, kinematics and bias forces for the state at t0
    if (!rk4) {
      mj_step1(&m, d);
      const StepFault fault = detector_.check_warnings(m, *d, t0);
      if (!fault.ok()) {
        stop(fault, result, recorder);
        return result;
      }
    } else if (s == 0 || compensate) {
      mj_forward(&m, d);
    }
    if (s == 0) {
      if (source != nullptr) {
        if (!source->update(*d, reference_)) {
          result.status = TickStatus::finished;
          result.time = d->time;
          return result;
        }
        reference = &reference_;
      }
      if (!run_controllers(*reference, result)) {
        stop(result.fault, result, recorder);
        return result;
      }
      if (recorder != nullptr) recorder->on_control_tick(*this, *reference);
    }
    if (compensate) compensate_gravity();
    // integrate: Euler finishes the split step, RK4 holds ctrl and qfrc_applied over its stages
    if (!rk4) {
      mj_step2(&m, d);
    } else {
      mj_step(&m, d);
    }
    StepFault fault = detector_.check_warnings(m, *d, t0);
    if (fault.ok()) fault = detector_.check_state(m, *d, t0);
    if (!fault.ok()) {
      stop(fault, result, recorder);
      return result;
    }
    ++steps_;
    if (recorder != nullptr) {
      recorder->on_physics_step(*this, t0, snapshot_.qpos(), snapshot_.qvel());
      const int warning = detector_.new_benign_warning(*d);
      if (warning >= 0) recorder->event(t0, "warning", warning_name(warning));
    }
  }
  ++ticks_;
  refresh_watches(true);
  result.time = d->time;
  return result;
}

bool Simulation::run_controllers(const Reference& reference, TickResult& result) noexcept {
  const mjData& d = *data_;
  for (int c = 0; c < controller_count(); ++c) {
    ControllerSlot& slot = controllers_[c];
    slot.controller->compute(d, reference, slot.command);
    const ApplyResult applied = slot.binding->apply(slot.command, data_->ctrl, saturated_.data());
    if (!applied.ok()) {
      StepFault& fault = result.fault;
      fault.cause = FaultCause::bad_command;
      fault.time = d.time;
      fault.controller = c;
      if (applied.bad_index >= 0) {
        fault.joint = slot.controller->chain().joint_id(applied.bad_index);
        fault.dof = slot.controller->chain().dof_address(applied.bad_index);
        fault.actuator = slot.binding->actuators()[applied.bad_index];
        fault.value = slot.command.value[applied.bad_index];
      }
      return false;
    }
    result.saturated += applied.saturated;
    for (int a : slot.binding->actuators()) saturation_counts_[a] += saturated_[a];
  }
  return true;
}

void Simulation::compensate_gravity() noexcept {
  // add this step's bias forces, replacing what the previous step added (the caller's own
  // qfrc_applied on these dofs is kept)
  mjData* d = data_.get();
  for (int dof : gravity_dofs_) {
    d->qfrc_applied[dof] += d->qfrc_bias[dof] - gravity_added_[dof];
    gravity_added_[dof] = d->qfrc_bias[dof];
  }
}

void Simulation::take_snapshot() noexcept {
  mj_getState(&model(), data_.get(), snapshot_.state.data(), snapshot_.spec);
}

void Simulation::restore_snapshot() noexcept {
  // MuJoCo may have reset the data after a bad value: put back the state of the step's start
  const mjModel& m = model();
  mjData* d = data_.get();
  mj_setState(&m, d, snapshot_.state.data(), snapshot_.spec);
  const std::span<const mjtNum> positions_and_velocities(snapshot_.qpos(),
                                                         static_cast<std::size_t>(m.nq + m.nv));
  if (all_finite(positions_and_velocities)) mj_forward(&m, d);
  detector_.rebase(*d);
}

void Simulation::stop(const StepFault& fault, TickResult& result, Recorder* recorder) {
  fault_ = fault;
  result.fault = fault;
  result.status =
      fault.cause == FaultCause::bad_command ? TickStatus::bad_command : TickStatus::diverged;
  restore_snapshot();
  result.time = data_->time;
  if (recorder != nullptr) {
    // the run ends here: formatting the message may allocate
    recorder->event(fault.time, fault.cause == FaultCause::bad_command ? "bad_command" : "divergence",
                    describe(fault));
  }
}

RunResult Simulation::run(ReferenceSource& source, double duration, Recorder* recorder) {
  if (options_.mode == SimulationMode::kinematic) {
    throw Error("simulation: run() needs position or torque mode; kinematic mode moves with move()");
  }
  if (!(std::isfinite(duration) && duration > 0.0)) {
    throw Error("simulation: run duration must be positive and finite, got " + number_text(duration) + " s");
  }
  if (recorder != nullptr) recorder->check_layout(*this);
  RunResult run;
  run.start_time = time();
  const std::int64_t ticks0 = ticks_;
  const std::int64_t steps0 = steps_;
  // whole control periods until the duration is covered (to half a physics step)
  const double end = run.start_time + duration - 0.5 * timestep();
  for (;;) {
    if (interrupt_requested()) {
      run.status = RunStatus::interrupted;
      break;
    }
    if (time() >= end) {
      run.status = RunStatus::duration_reached;
      break;
    }
    const TickResult tick = tick_impl(&source, nullptr, recorder);
    if (tick.ok()) continue;
    run.fault = tick.fault;
    run.status = tick.status == TickStatus::finished  ? RunStatus::finished
                 : tick.status == TickStatus::diverged ? RunStatus::diverged
                                                       : RunStatus::bad_command;
    break;
  }
  run.end_time = time();
  run.ticks = ticks_ - ticks0;
  run.physics_steps = steps_ - steps0;
  switch (run.status) {
    case RunStatus::duration_reached:
      run.message = "simulated " + seconds(run.end_time - run.start_time) + " (" +
                    std::to_string(run.ticks) + " control ticks)";
      break;
    case RunStatus::finished: run.message = "task finished at t = " + seconds(run.end_time); break;
    case RunStatus::interrupted:
      run.message = "interrupted by a signal at t = " + seconds(run.end_time);
      if (recorder != nullptr) recorder->event(run.end_time, "interrupt", run.message);
      break;
    case RunStatus::diverged:
    case RunStatus::bad_command: run.message = describe(run.fault); break;
  }
  if (recorder != nullptr) recorder->on_run_end(run);
  return run;
}

KinematicStep Simulation::move(std::span<const double> qpos, double dt, Recorder* recorder) {
  if (options_.mode != SimulationMode::kinematic) {
    throw Error("simulation: move() needs kinematic mode; this simulation runs in " +
                std::string(to_string(options_.mode)) + " mode");
  }
  const mjModel& m = model();
  mjData* d = data_.get();
  if (qpos.size() != static_cast<std::size_t>(m.nq)) {
    throw Error("simulation: move needs " + std::to_string(m.nq) + " qpos values, got " +
                std::to_string(qpos.size()));
  }
  for (std::size_t i = 0; i < qpos.size(); ++i) {
    if (!std::isfinite(qpos[i])) throw Error("simulation: move qpos[" + std::to_string(i) + "] is not finite");
  }
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw Error("simulation: move dt must be positive and finite, got " + number_text(dt) + " s");
  }
  take_snapshot();
  mj_differentiatePos(&m, d->qvel, dt, snapshot_.qpos(), qpos.data());
  std::copy(qpos.begin(), qpos.end(), d->qpos);
  d->time = snapshot_.time() + dt;
  mj_fwdPosition(&m, d);
  mj_sensorPos(&m, d);

  KinematicStep step;
  if (!options_.contact_check_a.empty()) {
    const ContactSummary touch =
        contact_between(m, *d, options_.contact_check_a, options_.contact_check_b, false);
    if (touch.contacts > 0) {
      step.rolled_back = true;
      step.geom_a = touch.first_geom_a;
      step.geom_b = touch.first_geom_b;
      mj_setState(&m, d, snapshot_.state.data(), snapshot_.spec);
      mj_fwdPosition(&m, d);
      mj_sensorPos(&m, d);
      if (recorder != nullptr) {
        const char* a = mj_id2name(&m, mjOBJ_GEOM, step.geom_a);
        const char* b = mj_id2name(&m, mjOBJ_GEOM, step.geom_b);
        recorder->event(snapshot_.time() + dt, "rollback",
                        "move would put geom '" + std::string(a ? a : "?") + "' in contact with geom '" +
                            std::string(b ? b : "?") + "'; rolled back");
      }
    }
  }
  if (!step.rolled_back) {
    ++steps_;
    if (recorder != nullptr) recorder->on_physics_step(*this, d->time, d->qpos, d->qvel);
  }
  refresh_watches(false);
  step.time = d->time;
  return step;
}

KinematicStep Simulation::move(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q,
                               double dt, Recorder* recorder) {
  if (&chain.robot().model() != &robot_.model()) {
    throw Error("simulation: move: chain of model '" + chain.robot().name() +
                "' used on a simulation of model '" + robot_.name() + "'");
  }
  chain.check(q, "move q");
  const mjData& d = *data_;
  move_qpos_.assign(d.qpos, d.qpos + model().nq);
  chain.scatter(q, move_qpos_.data());
  return move(move_qpos_, dt, recorder);
}

}  // namespace mjarm
