// sim room: Simulation (modes, ticks, sensors, contacts), reference sources, Recorder.
#include <optional>

#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"

namespace mjarm::python {
namespace {

/// A reference source written in Python: a callable f(data) -> Reference, or None/False when
/// the task is complete. Its exception ends the run (as finished) and is raised by the binding.
class PyFunctionSource final : public ReferenceSource {
 public:
  PyFunctionSource(const Robot& robot, py::function f) : robot_(robot), f_(std::move(f)) {}
  ~PyFunctionSource() override {
    py::gil_scoped_acquire gil;
    f_ = py::function();
  }
  bool update(const mjData& data, Reference& reference) noexcept override {
    py::gil_scoped_acquire gil;
    py::object handle;
    bool more = false;
    try {
      handle = py::cast(DataHandle(robot_, const_cast<mjData*>(&data), py::none()));
      const py::object out = f_(handle);
      if (out.is_none() || (py::isinstance<py::bool_>(out) && !out.cast<bool>())) {
        more = false;
      } else {
        reference = out.cast<const Reference&>();
        more = true;
      }
    } catch (...) {
      keep_callback_error(std::current_exception());
      more = false;
    }
    if (handle) handle.cast<DataHandle&>().valid = false;
    return more;
  }

 private:
  Robot robot_;
  py::function f_;
};

/// A `Recorder` with a Python lifetime: it keeps its simulation alive, `close()` (or leaving a
/// `with` block) finalizes it, and a recorder closed or finalized refuses further use.
struct RecorderHandle {
  std::unique_ptr<Recorder> recorder;
  py::object simulation;
  Recorder& get() const {
    if (!recorder) throw Error("Recorder: closed");
    return *recorder;
  }
};

Recorder* recorder_of(const std::optional<RecorderHandle*>& r) {
  return r && *r ? &(*r)->get() : nullptr;
}

/// Raises a kept callback error; its message also goes to the recording's events.
void finish_call(Simulation& sim, Recorder* recorder) {
  try {
    raise_callback_error();
  } catch (py::error_already_set& e) {
    if (recorder) recorder->event(sim.time(), "error", std::string("Python: ") + e.what());
    throw;
  } catch (std::exception& e) {
    if (recorder) recorder->event(sim.time(), "error", e.what());
    throw;
  }
}

bool in_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

void bind_sim(py::module_& m) {
  def_enum<SimulationMode>(m, "SimulationMode");
  def_enum<TickStatus>(m, "TickStatus");
  def_enum<RunStatus>(m, "RunStatus");
  def_enum<FaultCause>(m, "FaultCause");
  py::class_<StepFault>(m, "StepFault")
      .def_readonly("cause", &StepFault::cause, "what went wrong (none when healthy)")
      .def_readonly("time", &StepFault::time, "simulated time at the start of the failing step [s]")
      .def_readonly("joint", &StepFault::joint,
                    "joint id of the offending dof (−1 when not a joint)")
      .def_readonly("dof", &StepFault::dof, "index into qvel/qacc (or into qpos for qpos faults)")
      .def_readonly("actuator", &StepFault::actuator, "actuator id for ctrl faults")
      .def_readonly("controller", &StepFault::controller, "controller index for bad_command")
      .def_readonly("value", &StepFault::value, "the offending value")
      .def("ok", &StepFault::ok);
  py::class_<TickResult>(m, "TickResult")
      .def_readonly("status", &TickResult::status, "how the tick went")
      .def_readonly("time", &TickResult::time, "simulated time at the end of the tick [s]")
      .def_readonly("saturated", &TickResult::saturated,
                    "actuators clipped by this tick's commands")
      .def_readonly("fault", &TickResult::fault, "set when status is diverged or bad_command")
      .def("ok", &TickResult::ok);
  py::class_<RunResult>(m, "RunResult")
      .def_readonly("status", &RunResult::status, "how the run ended")
      .def_readonly("start_time", &RunResult::start_time, "simulated time when the run started [s]")
      .def_readonly("end_time", &RunResult::end_time, "simulated time when the run stopped [s]")
      .def_readonly("ticks", &RunResult::ticks, "control ticks simulated")
      .def_readonly("physics_steps", &RunResult::physics_steps, "physics steps simulated")
      .def_readonly("fault", &RunResult::fault, "the fault when diverged or bad_command")
      .def_readonly("message", &RunResult::message,
                    "one line for people: what happened, when, where")
      .def("ok", &RunResult::ok);
  py::class_<KinematicStep>(m, "KinematicStep")
      .def_readonly("rolled_back", &KinematicStep::rolled_back,
                    "True when the move made a contact and was undone")
      .def_readonly("geom_a", &KinematicStep::geom_a,
                    "geom of set A of the contact that caused the rollback (−1 when none)")
      .def_readonly("geom_b", &KinematicStep::geom_b,
                    "geom of set B of the contact that caused the rollback (−1 when none)")
      .def_readonly("time", &KinematicStep::time, "simulated time after the call [s]");

  py::class_<GeomSet>(m, "GeomSet", "A set of geoms of one model.")
      .def(py::init<>())
      .def_static("of_bodies", &GeomSet::of_bodies, py::arg("robot"), py::arg("bodies"),
                  py::arg("subtree") = true)
      .def_static("of_geoms", &GeomSet::of_geoms, py::arg("robot"), py::arg("geoms"))
      .def("complement", &GeomSet::complement, py::arg("robot"))
      .def("add", &GeomSet::add, py::arg("other"), py::return_value_policy::reference_internal)
      .def("contains", &GeomSet::contains, py::arg("geom"))
      .def_property_readonly("size", &GeomSet::size, "number of geoms in the set")
      .def("__len__", &GeomSet::size);
  py::class_<ContactSummary>(m, "ContactSummary", "Contacts between two geom sets, summed.")
      .def_readonly("contacts", &ContactSummary::contacts,
                    "active contacts between A and B (within the geoms' margins)")
      .def_readonly("min_distance", &ContactSummary::min_distance, "[m], +inf when none")
      .def_property_readonly(
          "force_W", [](const ContactSummary& c) { return Eigen::Vector3d(c.force_W); },
          "force A exerts on B, world (3,) [N]")
      .def_readonly("normal_force", &ContactSummary::normal_force,
                    "sum of the normal components of the contact forces [N] (≥ 0)")
      .def_readonly("forces_valid", &ContactSummary::forces_valid,
                    "False when the data held no constraint forces (kinematic mode): only counts "
                    "and distances mean something")
      .def_readonly("first_geom_a", &ContactSummary::first_geom_a,
                    "geom id on side A of the first contact found (−1 when none)")
      .def_readonly("first_geom_b", &ContactSummary::first_geom_b,
                    "geom id on side B of the first contact found (−1 when none)");

  py::class_<SimulationOptions> simulation_options(m, "SimulationOptions");
  simulation_options.def(py::init<>())
      .def(py::init([](SimulationMode mode, double period) {
             SimulationOptions o;
             o.mode = mode;
             o.control_period = period;
             return o;
           }),
           py::arg("mode"), py::arg("control_period") = 0.0)
      .def_readwrite("contact_check_a", &SimulationOptions::contact_check_a,
                     "kinematic mode: a move putting a geom of this set in contact with one of "
                     "contact_check_b is rolled back (empty: no check)")
      .def_readwrite("contact_check_b", &SimulationOptions::contact_check_b,
                     "the other side of the contact check (empty with a non-empty contact_check_a: "
                     "any other geom)");
  def_fields(simulation_options);

  py::class_<ReferenceSource>(m, "ReferenceSource", "Produces each control tick's reference.");
  py::class_<ConstantReferenceSource, ReferenceSource>(m, "ConstantReferenceSource",
                                                       "Gives the same Reference every tick.")
      .def(py::init<Reference>(), py::arg("reference"));
  py::class_<PyFunctionSource, ReferenceSource>(
      m, "FunctionReferenceSource",
      "A Python callable f(data) -> Reference (None or False: the task is complete). data is "
      "valid during the call only.")
      .def(py::init<const Robot&, py::function>(), py::arg("robot"), py::arg("function"));

  py::class_<Simulation>(m, "Simulation",
                         "One simulated robot: owns its mjData, runs controllers at the control "
                         "period, checks every physics step for divergence. tick() and run() "
                         "release the GIL (a Python controller takes it back for its call).")
      .def(py::init<const Robot&, const SimulationOptions&>(), py::arg("robot"),
           py::arg("options") = SimulationOptions{})
      .def_property_readonly("robot", &Simulation::robot, "the simulated model")
      .def_property_readonly("options", &Simulation::options, "the simulation's options")
      .def_property_readonly("mode", &Simulation::mode,
                             "how the robot moves: kinematic, position or torque")
      .def_property_readonly("timestep", &Simulation::timestep, "physics timestep [s]")
      .def_property_readonly("control_period", &Simulation::control_period, "control period [s]")
      .def_property_readonly("steps_per_tick", &Simulation::steps_per_tick,
                             "physics steps per control tick")
      .def_property_readonly("time", &Simulation::time, "simulated time [s]")
      .def_property_readonly("ticks", &Simulation::ticks, "control ticks since reset")
      .def_property_readonly("physics_steps", &Simulation::physics_steps,
                             "physics steps since reset")
      .def_property_readonly(
          "data",
          [](py::object self) {
            auto& sim = self.cast<Simulation&>();
            return DataHandle(sim.robot(), &sim.data(), self);
          },
          "The simulation's Data: read-only views that keep the simulation alive.")
      .def_property_readonly(
          "qpos",
          [](py::object self) {
            auto& sim = self.cast<Simulation&>();
            return readonly_view(sim.data().qpos, sim.model().nq, self);
          },
          "read-only view of qpos (nq,); it follows the simulation and keeps it alive")
      .def_property_readonly(
          "qvel",
          [](py::object self) {
            auto& sim = self.cast<Simulation&>();
            return readonly_view(sim.data().qvel, sim.model().nv, self);
          },
          "read-only view of qvel (nv,)")
      .def_property_readonly(
          "ctrl",
          [](py::object self) {
            auto& sim = self.cast<Simulation&>();
            return readonly_view(sim.data().ctrl, sim.model().nu, self);
          },
          "read-only view of ctrl (nu,)")
      .def(
          "reset",
          [](Simulation& s, std::optional<std::string> keyframe) {
            clear_callback_error();
            keyframe ? s.reset(*keyframe) : s.reset();
            raise_callback_error();
          },
          py::arg("keyframe") = py::none(),
          "mj_resetData (or a keyframe), forward, controllers reset")
      .def(
          "set_state",
          [](Simulation& s, py::handle qpos, py::handle qvel) {
            const Eigen::VectorXd q = to_vector(qpos, "qpos", s.model().nq);
            const Eigen::VectorXd v = to_vector(qvel, "qvel", s.model().nv);
            s.set_state({q.data(), static_cast<size_t>(q.size())},
                        {v.data(), static_cast<size_t>(v.size())});
          },
          py::arg("qpos"), py::arg("qvel"))
      .def("forward", &Simulation::forward)
      .def("add_controller", &Simulation::add_controller, py::arg("controller"),
           py::keep_alive<1, 2>(), "Adds a controller (kept alive by the simulation).")
      .def_property_readonly("controller_count", &Simulation::controller_count,
                             "number of controllers added")
      .def(
          "command", [](const Simulation& s, int i) { return Eigen::VectorXd(s.command(i).value); },
          py::arg("i"), "the command controller i wrote at the last tick (n,)")
      .def_property_readonly(
          "saturated",
          [](const Simulation& s) {
            const auto f = s.saturated();
            return std::vector<int>(f.begin(), f.end());
          },
          "one flag per actuator: 1 when the last tick's command was clipped on it")
      .def_property_readonly(
          "saturation_counts",
          [](const Simulation& s) {
            const auto c = s.saturation_counts();
            return std::vector<std::int64_t>(c.begin(), c.end());
          },
          "per actuator: how many ticks its command was clipped since reset")
      .def(
          "tick",
          [](Simulation& s, py::handle what, std::optional<RecorderHandle*> recorder) {
            Recorder* rec = recorder_of(recorder);
            TickResult r;
            clear_callback_error();
            if (py::isinstance<Reference>(what)) {
              const Reference& ref = what.cast<const Reference&>();
              py::gil_scoped_release release;
              r = s.tick(ref, rec);
            } else if (py::isinstance<ReferenceSource>(what)) {
              ReferenceSource& source = what.cast<ReferenceSource&>();
              py::gil_scoped_release release;
              r = s.tick(source, rec);
            } else {
              throw py::type_error("tick: expected a Reference or a ReferenceSource");
            }
            finish_call(s, rec);
            return r;
          },
          py::arg("reference"), py::arg("recorder") = py::none(),
          "One control tick with a Reference or from a ReferenceSource.")
      .def(
          "run",
          [](Simulation& s, ReferenceSource& source, double duration,
             std::optional<RecorderHandle*> recorder) {
            Recorder* rec = recorder_of(recorder);
            RunResult r;
            clear_callback_error();
            {
              // Ctrl-C ends the run cleanly (status interrupted) instead of waiting for its end
              std::optional<InterruptGuard> guard;
              if (in_main_thread()) guard.emplace();
              py::gil_scoped_release release;
              r = s.run(source, duration, rec);
            }
            finish_call(s, rec);
            if (r.status == RunStatus::interrupted) {
              clear_interrupt();
              PyErr_SetNone(PyExc_KeyboardInterrupt);
              throw py::error_already_set();
            }
            return r;
          },
          py::arg("source"), py::arg("duration"), py::arg("recorder") = py::none(),
          "Ticks until duration [s] passed, the source finishes, a fault, or Ctrl-C "
          "(KeyboardInterrupt, the recording's events have it).")
      .def(
          "move",
          [](Simulation& s, py::handle qpos, double dt, std::optional<RecorderHandle*> recorder) {
            const Eigen::VectorXd q = to_vector(qpos, "qpos", s.model().nq);
            return s.move({q.data(), static_cast<size_t>(q.size())}, dt, recorder_of(recorder));
          },
          py::arg("qpos"), py::arg("dt"), py::arg("recorder") = py::none(),
          "Kinematic mode: sets qpos (nq,), advances dt [s].")
      .def(
          "move_chain",
          [](Simulation& s, const Chain& chain, py::handle q, double dt,
             std::optional<RecorderHandle*> recorder) {
            return s.move(chain, to_vector(q, "q", chain.size()), dt, recorder_of(recorder));
          },
          py::arg("chain"), py::arg("q"), py::arg("dt"), py::arg("recorder") = py::none())
      .def_property_readonly("fault", &Simulation::fault,
                             "the last fault (cause none when healthy)")
      .def("describe", &Simulation::describe, py::arg("fault"))
      .def(
          "sensor",
          [](py::object self, std::string_view name) {
            auto& sim = self.cast<Simulation&>();
            const auto v = sim.sensor(name);
            return readonly_view(v.data(), static_cast<Eigen::Index>(v.size()), self);
          },
          py::arg("name"), "read-only view of a sensor's values")
      .def("watch_contacts", &Simulation::watch_contacts, py::arg("a"), py::arg("b") = GeomSet{},
           "watches contacts between a and b (empty b: anything else); returns a handle")
      .def("contacts", &Simulation::contacts, py::arg("handle"));

  py::class_<RecorderOptions> recorder_options(m, "RecorderOptions");
  recorder_options.def(py::init<>());
  def_fields(recorder_options);
  py::class_<RecorderHandle>(m, "Recorder",
                             "Records a Simulation into a directory (state/task/events CSV + "
                             "summary.json, atomic). Use as a context manager, or call finalize().")
      .def(py::init([](py::object sim, const std::filesystem::path& dir, const RecorderOptions& o) {
             RecorderHandle h;
             h.recorder = std::make_unique<Recorder>(sim.cast<const Simulation&>(), dir, o);
             h.simulation = std::move(sim);
             return h;
           }),
           py::arg("simulation"), py::arg("directory"), py::arg("options") = RecorderOptions{})
      .def(
          "event",
          [](RecorderHandle& h, double t, std::string_view kind, std::string_view message) {
            h.get().event(t, kind, message);
          },
          py::arg("time"), py::arg("kind"), py::arg("message"))
      .def("flush", [](RecorderHandle& h) { h.get().flush(); })
      .def(
          "finalize",
          [](RecorderHandle& h, std::string_view status, std::string_view message) {
            h.get().finalize(status, message);
          },
          py::arg("status"), py::arg("message") = "")
      .def(
          "finalize_run", [](RecorderHandle& h, const RunResult& r) { h.get().finalize(r); },
          py::arg("result"), "finalize with a run's status and message")
      .def(
          "close", [](RecorderHandle& h) { h.recorder.reset(); },
          "finalizes (with the last run's status) if not finalized, and closes")
      .def_property_readonly(
          "finalized",
          [](const RecorderHandle& h) { return !h.recorder || h.recorder->finalized(); },
          "True once the recording was finalized (or closed)")
      .def_property_readonly(
          "directory", [](const RecorderHandle& h) { return h.get().directory(); },
          "the recording directory (where the files end up)")
      .def_property_readonly(
          "state_path", [](const RecorderHandle& h) { return h.get().state_path(); },
          "final path of state.csv")
      .def_property_readonly(
          "task_path", [](const RecorderHandle& h) { return h.get().task_path(); },
          "final path of task.csv")
      .def_property_readonly(
          "events_path", [](const RecorderHandle& h) { return h.get().events_path(); },
          "final path of events.csv")
      .def_property_readonly(
          "summary_path", [](const RecorderHandle& h) { return h.get().summary_path(); },
          "final path of summary.json")
      .def_property_readonly(
          "state_rows", [](const RecorderHandle& h) { return h.get().state_rows(); },
          "rows written to state.csv")
      .def_property_readonly(
          "task_rows", [](const RecorderHandle& h) { return h.get().task_rows(); },
          "rows written to task.csv")
      .def_property_readonly(
          "event_rows", [](const RecorderHandle& h) { return h.get().event_rows(); },
          "rows written to events.csv")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](RecorderHandle& h, py::object type, py::object value, py::object) {
        if (h.recorder && !h.recorder->finalized()) {
          if (!type.is_none()) {
            // the run ended with an exception: the recording is kept, marked as such
            h.recorder->finalize("error", py::str(value).cast<std::string>());
          }
        }
        h.recorder.reset();
        return false;
      });
}

}  // namespace mjarm::python
