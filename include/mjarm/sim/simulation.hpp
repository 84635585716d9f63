#pragma once
/// @file
/// `Simulation`: owns the `mjData` of one robot and advances it in kinematic, position or torque
/// mode, running controllers at the control period and checking every physics step for
/// divergence. See docs/simulation.md.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/control/controller.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/actuator_binding.hpp"
#include "mjarm/sim/contact_query.hpp"
#include "mjarm/sim/run_result.hpp"
#include "mjarm/sim/simulation_options.hpp"
#include "mjarm/sim/state_snapshot.hpp"
#include "mjarm/sim/step_fault.hpp"

namespace mjarm {

class Recorder;

/// Outcome of a kinematic `Simulation::move`.
struct KinematicStep {
  bool rolled_back = false;  ///< true when the move made a contact and was undone
  int geom_a = -1;           ///< the contact that caused the rollback: geom of set A …
  int geom_b = -1;           ///< … and geom of set B (ids; −1 when none)
  double time = 0.0;         ///< simulated time after the call [s]
};

/// One simulated robot: the `mjData`, the controllers that drive it and the loop that runs them.
///
/// Control tick (Euler integrator), repeated every control period:
///   mj_step1 → reference source → controllers → ctrl (and gravity compensation) → mj_step2,
///   then the remaining physics steps of the period (each mj_step1 → compensation → mj_step2).
/// With RK4: mj_forward → source → controllers → ctrl → mj_step (see docs/simulation.md).
/// Every physics step is checked for divergence; a fault stops the simulation (ticks return it)
/// until `reset` or `set_state`, and the state of the last good step is restored.
class Simulation {
 public:
  /// @throws Error when the model's timestep is not positive and finite, the control period is
  ///         not a positive whole multiple of it, or max_acceleration is not positive.
  explicit Simulation(const Robot& robot, const SimulationOptions& options = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // ---- model, data, timing ----
  const Robot& robot() const noexcept { return robot_; }
  /// The model this simulation steps: the robot's shared model, or the simulation's own copy
  /// once it has one (`SimulationOptions::own_model` for domain randomization, `own_model()` for
  /// a weld grasp, whose relative pose is model data); `robot().model()` keeps the values of the
  /// file either way. Switching equality constraints on and off needs no copy (`eq_active` is
  /// state, in `mjData`).
  const mjModel& model() const noexcept { return *model_; }
  /// True when `model()` is this simulation's own copy.
  bool owns_model() const noexcept { return own_model_ != nullptr; }
  /// Gives this simulation its own copy of the model from now on (nothing happens when it has
  /// one already). The data keeps its state: the copy has the same layout.
  /// @throws Error when MuJoCo cannot copy the model.
  void own_model();
  /// The simulation's own model copy, for its owner to edit between steps (masses, friction,
  /// damping, gains, sizes; call `mj_setConst` after changing masses or inertias), or null when
  /// the model is the robot's shared one. Controllers keep reading the robot's model for its
  /// structure and the state's dynamics (mass matrix, bias forces) from the data.
  mjModel* editable_model() noexcept { return own_model_.get(); }
  /// The simulation's data. Writing qpos/qvel directly is allowed; call `forward` afterwards.
  mjData& data() noexcept { return *data_; }
  const mjData& data() const noexcept { return *data_; }
  const SimulationOptions& options() const noexcept { return options_; }
  SimulationMode mode() const noexcept { return options_.mode; }
  double timestep() const noexcept { return model_->opt.timestep; }                ///< [s]
  double control_period() const noexcept { return timestep() * steps_per_tick_; }  ///< [s]
  int steps_per_tick() const noexcept { return steps_per_tick_; }
  double time() const noexcept { return data_->time; }  ///< simulated time [s]
  bool uses_rk4() const noexcept { return model_->opt.integrator == mjINT_RK4; }
  std::int64_t ticks() const noexcept { return ticks_; }          ///< control ticks since reset
  std::int64_t physics_steps() const noexcept { return steps_; }  ///< physics steps since reset

  // ---- state ----
  /// mj_resetData's state (or the keyframe @p keyframe), mj_forward, controllers
  /// reset, fault cleared.
  /// @throws Error for an unknown keyframe.
  void reset();
  void reset(std::string_view keyframe);
  /// Writes the full qpos (nq) and qvel (nv), then mj_forward; clears a fault.
  /// @throws Error on wrong sizes or NaN/inf.
  void set_state(std::span<const double> qpos, std::span<const double> qvel);
  /// Everything in `mjData` that determines the next tick (`StateSnapshot`); the controllers' and
  /// reference sources' own state is not in it.
  StateSnapshot snapshot() const { return StateSnapshot::of(model(), *data_); }
  /// Puts @p snapshot back and recomputes the derived quantities (mj_forward): the ticks that
  /// follow are the ones that followed the snapshot, bit for bit, for stateless controllers;
  /// clears a fault.
  /// @throws Error when @p snapshot was taken of another model.
  void restore(const StateSnapshot& snapshot);
  /// mj_forward: recomputes everything derived from qpos/qvel/ctrl. Between ticks the derived
  /// quantities lag one physics step (they belong to the start of the last step); calling this
  /// makes them current; it writes no part of the integration state, so the ticks that follow
  /// are unchanged (MuJoCo 4.0.1).
  void forward();

  // ---- controllers ----
  /// Adds a controller; each tick it runs in the order added, several per tick (arm, gripper).
  /// The simulation keeps a reference: @p controller must outlive it.
  /// @throws Error when the mode takes no controllers (kinematic) or another kind of command,
  ///         when its chain belongs to another model, when a joint lacks a fitting actuator, or
  ///         when an actuator is already commanded by another controller, or when the controller
  ///         compensates the bias forces itself (`Controller::compensates_bias`) in position mode
  ///         with `SimulationOptions::gravity_compensation` on (the bias would count twice).
  void add_controller(Controller& controller);
  int controller_count() const noexcept { return static_cast<int>(controllers_.size()); }
  Controller& controller(int i) const { return *controllers_.at(i).controller; }
  /// The command controller i wrote at the last tick.
  const JointCommand& command(int i) const { return controllers_.at(i).command; }
  const ActuatorBinding& binding(int i) const { return *controllers_.at(i).binding; }

  /// One flag per actuator: 1 when the last tick's command was clipped on it.
  std::span<const std::uint8_t> saturated() const noexcept { return saturated_; }
  /// Per actuator: how many ticks its command was clipped since reset.
  std::span<const std::int64_t> saturation_counts() const noexcept { return saturation_counts_; }

  // ---- stepping ----
  /// One control tick with a fixed reference. Allocation-free.
  /// @throws Error in kinematic mode (use `move`).
  TickResult tick(const Reference& reference, Recorder* recorder = nullptr);
  /// One control tick; @p source fills the reference after the kinematics are fresh.
  TickResult tick(ReferenceSource& source, Recorder* recorder = nullptr);

  /// Ticks until @p duration [s] of simulated time passed, the source finishes, a step diverges,
  /// a controller writes NaN, or an interrupt arrives (mjarm/interrupt.hpp). Faults and
  /// interrupts are also written to the recorder's events; the recorder is not finalized here.
  /// @throws Error when @p duration is not positive and finite, in kinematic mode, or when
  ///         @p recorder was built for another simulation.
  RunResult run(ReferenceSource& source, double duration, Recorder* recorder = nullptr);

  /// Kinematic mode: sets qpos (nq), qvel = finite difference over @p dt, advances time by @p dt
  /// and computes the position stage (kinematics, collision, sensors of positions). When the
  /// contact check is on and the new qpos touches, everything is rolled back and reported.
  /// @throws Error outside kinematic mode, for a wrong size, NaN/inf or dt ≤ 0.
  KinematicStep move(std::span<const double> qpos, double dt, Recorder* recorder = nullptr);
  /// Same, for the joints of @p chain (the other coordinates keep their values).
  KinematicStep move(const Chain& chain, const Eigen::Ref<const Eigen::VectorXd>& q, double dt,
                     Recorder* recorder = nullptr);

  /// The last fault (cause none when the simulation is healthy).
  const StepFault& fault() const noexcept { return fault_; }
  /// A sentence describing @p fault (time, cause, joint or controller).
  std::string describe(const StepFault& fault) const;

  // ---- equality constraints ----
  /// Id of the equality constraint called @p name.
  /// @throws Error naming the model's equality constraints closest to @p name.
  int equality(std::string_view name) const;
  /// Whether equality @p id is switched on. @throws Error for an id out of range.
  bool equality_active(int id) const;
  /// Switches equality @p id on or off (`mjData::eq_active`); the next step sees it. A reset
  /// restores the model's `eq_active0`. Allocation-free; returns false (nothing changed) for an
  /// id out of range.
  bool set_equality_active(int id, bool active) noexcept;
  /// The constraint data of equality @p id (mjNEQDATA values: for a weld, the anchor in body2's
  /// frame [0..2], the pose of body2 in body1's frame, position [3..5] and quaternion w x y z
  /// [6..9], the torque scale [10], and [11] nonzero when the compiler computed the pose at
  /// qpos0). Empty for an id out of range.
  std::span<const double> equality_data(int id) const noexcept;
  /// Writes the data of equality @p id (mjNEQDATA values, see `equality_data`) into this
  /// simulation's own model (`own_model()`). Allocation-free; false (nothing written) without an
  /// own model, for an id out of range, a wrong size or a non-finite value.
  bool set_equality_data(int id, std::span<const double> values) noexcept;
  /// Sets the solver reference of equality @p id in this simulation's own model: time constant
  /// [s] and damping ratio.
  /// @throws Error for an id out of range, values that are not positive and finite, or without
  ///         an own model (`own_model()`).
  void set_equality_solref(int id, double time_constant, double damping_ratio);

  // ---- sensors and contacts ----
  /// Values of the sensor called @p name (fresh as of the start of the last physics step).
  /// @throws Error for an unknown sensor (listing close names).
  std::span<const double> sensor(std::string_view name) const;
  /// Values of sensor id @p id, without a name lookup.
  std::span<const double> sensor(int id) const;

  /// Watches the contacts between @p a and @p b (empty b = anything else); returns a handle for
  /// `contacts`. The summary is refreshed after every tick from the last step's contacts and
  /// constraint forces (and after reset/set_state/forward/move).
  int watch_contacts(const GeomSet& a, const GeomSet& b);
  /// The summary of watch @p handle.
  const ContactSummary& contacts(int handle) const { return watches_.at(handle).summary; }

 private:
  struct ControllerSlot {
    Controller* controller = nullptr;
    JointCommand command;
    std::unique_ptr<ActuatorBinding> binding;
  };
  struct Watch {
    GeomSet a, b;
    ContactSummary summary;
  };
  /// The whole integration state at the start of a physics step (mj_getState with
  /// mjSTATE_INTEGRATION: time, qpos, qvel, act, warm start, controls, applied forces, mocap,
  /// eq_active, ...), for the recorder's rows and the rollback. `spec` leaves out the
  /// components the model has none of (no mocap body, no plugin, ...): the same values, at half
  /// the cost of a snapshot per physics step.
  struct Snapshot {
    std::vector<mjtNum> state;
    int spec = mjSTATE_INTEGRATION;
    int nq = 0;
    double time() const noexcept { return state[0]; }
    const mjtNum* qpos() const noexcept { return state.data() + 1; }  // after time
    const mjtNum* qvel() const noexcept { return state.data() + 1 + nq; }
  };

  TickResult tick_impl(ReferenceSource* source, const Reference* reference, Recorder* recorder);
  bool run_controllers(const Reference& reference, TickResult& result) noexcept;
  void compensate_gravity() noexcept;
  void take_snapshot() noexcept;
  void restore_snapshot() noexcept;
  void stop(const StepFault& fault, TickResult& result, Recorder* recorder);
  void refresh_watches(bool with_forces) noexcept;
  void after_reset();

  struct ModelDeleter {
    void operator()(mjModel* m) const noexcept { mj_deleteModel(m); }
  };

  Robot robot_;
  std::unique_ptr<mjModel, ModelDeleter> own_model_;  // own_model option or own_model()
  const mjModel* model_ = nullptr;                    // own_model_ or the robot's
  SimulationOptions options_;
  DataPtr data_;
  int steps_per_tick_ = 1;
  std::vector<ControllerSlot> controllers_;
  std::vector<int> commanded_by_;      // per actuator: controller index or −1
  std::vector<int> gravity_dofs_;      // dofs compensated in position mode
  std::vector<double> gravity_added_;  // what compensate_gravity added to qfrc_applied, per dof
  std::vector<std::uint8_t> saturated_;
  std::vector<std::int64_t> saturation_counts_;
  std::vector<Watch> watches_;
  DivergenceDetector detector_;
  StepFault fault_;
  Snapshot snapshot_;
  Reference reference_;            // filled by a source each tick (reused storage)
  std::vector<double> move_qpos_;  // scratch full qpos for the chain form of move
  std::int64_t ticks_ = 0;
  std::int64_t steps_ = 0;
};

}  // namespace mjarm
