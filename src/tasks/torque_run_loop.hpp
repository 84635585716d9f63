#pragma once
// The tick loop of the torque-mode task runs (docking, the tracking gate, wiping):
// `Simulation::run` with a hook after every tick, where the contacts and constraint forces of
// the step just taken are consistent (a reference source runs before them). Internal to the
// tasks room.

#include <cstdint>
#include <cstdio>

#include "mjarm/interrupt.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm::torque_run {

/// Ticks @p sim with @p source until the source finishes, a step diverges, a controller writes
/// NaN or an interrupt arrives, calling @p after_tick() after every good tick. The message says
/// what happened ("@p what finished at t = … s (N control ticks)"); an interrupt is written to
/// the recorder's events; the recorder is told how the run ended, not finalized.
template <class AfterTick>
RunResult run_ticks(Simulation& sim, ReferenceSource& source, Recorder* recorder, const char* what,
                    AfterTick&& after_tick) {
  RunResult run;
  run.start_time = sim.time();
  const std::int64_t ticks0 = sim.ticks();
  const std::int64_t steps0 = sim.physics_steps();
  for (;;) {
    if (interrupt_requested()) {
      run.status = RunStatus::interrupted;
      break;
    }
    const TickResult tick = sim.tick(source, recorder);
    if (!tick.ok()) {
      run.fault = tick.fault;
      run.status = tick.status == TickStatus::finished   ? RunStatus::finished
                   : tick.status == TickStatus::diverged ? RunStatus::diverged
                                                         : RunStatus::bad_command;
      break;
    }
    after_tick();
  }
  run.end_time = sim.time();
  run.ticks = sim.ticks() - ticks0;
  run.physics_steps = sim.physics_steps() - steps0;
  char line[160];
  switch (run.status) {
    case RunStatus::finished:
    case RunStatus::duration_reached:
      std::snprintf(line, sizeof line, "%s finished at t = %.3f s (%lld control ticks)", what,
                    run.end_time, static_cast<long long>(run.ticks));
      run.message = line;
      break;
    case RunStatus::interrupted:
      std::snprintf(line, sizeof line, "interrupted by a signal at t = %.3f s", run.end_time);
      run.message = line;
      if (recorder != nullptr) recorder->event(run.end_time, "interrupt", run.message);
      break;
    case RunStatus::diverged:
    case RunStatus::bad_command:
      run.message = sim.describe(run.fault);
      break;
  }
  if (recorder != nullptr) recorder->on_run_end(run);
  return run;
}

/// Makes the start of @p sim (set by `set_state`, at rest) one where the arm is already held:
/// each motor of @p chain commands the bias torque (gravity, at rest) and mj_forward recomputes
/// the sensors. The first tick's force/torque reading is one physics step old; without this it
/// belongs to the arm falling under zero torque, where the sensor carries nothing and reads the
/// whole tool weight as an external force (2.1 N), which latched HQP-AC's contact and its preload
/// in free space. A real arm's controller holds it before the task begins.
inline void start_held(Simulation& sim, const Chain& chain) {
  const mjModel& m = sim.model();
  mjData& d = sim.data();
  for (int i = 0; i < chain.size(); ++i) {
    const std::optional<int> a = chain.actuator(i);
    if (!a) continue;
    const double gain = m.actuator_gear[6 * *a] * m.actuator_gainprm[mjNGAIN * *a];
    if (gain != 0.0) d.ctrl[*a] = d.qfrc_bias[chain.dof_address(i)] / gain;
  }
  sim.forward();
}

/// A torque-mode simulation of @p robot at its own timestep with the divergence bound
/// @p max_acceleration.
inline SimulationOptions torque_simulation(double max_acceleration) {
  SimulationOptions options;
  options.mode = SimulationMode::torque;
  options.max_acceleration = max_acceleration;
  return options;
}

}  // namespace mjarm::torque_run
