// ik room: position DLS, pose IK, multi-target, differential-IK QP with its constraints, global
// IK, closed-form 6R IK; options, IkResult.
#include <pybind11/functional.h>

#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/ik/analytic_ik.hpp"
#include "mjarm/ik/collision_avoidance.hpp"
#include "mjarm/ik/configuration_limit.hpp"
#include "mjarm/ik/diff_ik.hpp"
#include "mjarm/ik/global_ik.hpp"
#include "mjarm/ik/local_ik_settings.hpp"
#include "mjarm/ik/manipulability_barrier.hpp"
#include "mjarm/ik/multi_target_ik.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/ik/position_ik.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mujoco_interop.hpp"

namespace mjarm::python {
namespace {

/// Makes constraint C from @p options on the DiffIk's chain and adds it; the DiffIk owns it.
template <class C, class Options>
C& add_constraint(DiffIk& ik, const Options& options) {
  return static_cast<C&>(
      ik.constraint(ik.add_constraint(std::make_unique<C>(ik.chain(), options))));
}

/// An `IkIterationCallback` that calls a Python function with (iteration, position_error,
/// orientation_error, q) under the GIL; an exception it raises is kept and raised by the solve.
IkIterationCallback python_observer(py::object f) {
  if (f.is_none()) return nullptr;
  auto fn = std::make_shared<py::object>(std::move(f));
  // the solver's copy of the std::function may be destroyed without the GIL: release the
  // Python object under it
  auto holder = std::shared_ptr<py::object>(fn.get(), [fn](py::object*) mutable {
    py::gil_scoped_acquire gil;
    fn.reset();
  });
  return [holder](const IkIteration& it) {
    py::gil_scoped_acquire gil;
    try {
      (*holder)(it.iteration, it.position_error, it.orientation_error,
                it.q ? to_array(it.q->data(), it.q->size()) : py::array_t<double>());
    } catch (py::error_already_set&) {
      keep_callback_error(std::current_exception());
    }
  };
}

/// Runs @p solve without the GIL and raises an observer's exception afterwards.
template <typename F>
IkResult solve_released(F&& solve) {
  clear_callback_error();
  IkResult r;
  {
    py::gil_scoped_release release;
    r = solve();
  }
  raise_callback_error();
  return r;
}

/// One solve per target from the same seed, the GIL released for the whole batch; an observer's
/// exception is raised afterwards.
template <typename Ik, typename Target>
std::vector<IkResult> solve_each(Ik& ik, const std::vector<Target>& targets,
                                 const Eigen::VectorXd& q_seed) {
  std::vector<IkResult> results(targets.size());
  clear_callback_error();
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < targets.size(); ++i) ik.solve(targets[i], q_seed, results[i]);
  }
  raise_callback_error();
  return results;
}

std::vector<Pose> poses_of(const std::vector<py::object>& targets) {
  std::vector<Pose> poses;
  for (const auto& t : targets) poses.push_back(to_pose(t, "X_WT"));
  return poses;
}

/// The seed: joint values, or where the arm is now in a Simulation, a Data or a mujoco.MjData of
/// the chain's model (the seeds' idiom: solve from the current state).
Eigen::VectorXd seed_of(const Chain& chain, py::handle q_seed) {
  const auto current = [&](const DataHandle& h) {
    return chain.gather(data_of(chain.robot(), h, "solve", "the chain's model").qpos);
  };
  if (py::isinstance<DataHandle>(q_seed)) return current(q_seed.cast<const DataHandle&>());
  if (py::isinstance<Simulation>(q_seed)) {
    auto& sim = q_seed.cast<Simulation&>();
    return current(
        DataHandle(sim.robot(), &sim.data(), py::reinterpret_borrow<py::object>(q_seed)));
  }
  if (is_mujoco_data(q_seed)) return current(data_from_mujoco(q_seed));
  return to_vector(q_seed, "q_seed", chain.size());
}

}  // namespace

void bind_ik(py::module_& m) {
  def_enum<IkStatus>(m, "IkStatus", "How an IK solve ended.");
  py::class_<IkResult>(m, "IkResult", "The best configuration found, with its errors.")
      .def(py::init<>())
      .def_readonly("q", &IkResult::q, "joint values (n,)")
      .def_readonly("status", &IkResult::status, "converged, or why the solve stopped")
      .def_readonly("position_error", &IkResult::position_error,
                    "‖p_target − p‖, worst target for multi-target [m]")
      .def_readonly("orientation_error", &IkResult::orientation_error,
                    "rotation angle between target and achieved [rad]")
      .def_readonly("iterations", &IkResult::iterations, "iterations run (all restarts together)")
      .def("ok", &IkResult::ok, "status is converged")
      .def("__repr__", [](const IkResult& r) {
        return std::string("<IkResult ") + to_string(r.status) + " after " +
               std::to_string(r.iterations) + " iterations, " + number_text(r.position_error) +
               " m, " + number_text(r.orientation_error) + " rad>";
      });

  py::class_<LimitBias> limit_bias(m, "LimitBias",
                                   "Centre pull and limit repulsion (per-iteration steps).");
  limit_bias.def(py::init<>())
      .def(py::init([](double c, double r, double z) {
             return LimitBias{c, r, z};
           }),
           py::arg("centre_gain"), py::arg("repulsion_gain") = 0.0,
           py::arg("repulsion_zone") = 0.15);
  def_fields(limit_bias);
  py::class_<Posture> posture(m, "Posture", "A preferred configuration (null-space pull).");
  posture.def(py::init<>());
  def_fields(posture);
  py::class_<CollisionSpec> collision(m, "CollisionSpec",
                                      "Geoms that must not touch during a solve.");
  collision.def(py::init<>());
  def_fields(collision);

  // the fields every local solver's options share, bound once on their common base
  py::class_<LocalIkSettings> settings(m, "LocalIkSettings",
                                       "The settings every local IK solver shares: "
                                       "PositionIkOptions, PoseIkOptions and MultiTargetIkOptions "
                                       "derive from it, each with its own defaults.");
  def_fields(settings);
  settings.def_property(
      "on_iteration", [](const LocalIkSettings& o) { return static_cast<bool>(o.on_iteration); },
      [](LocalIkSettings& o, py::object f) { o.on_iteration = python_observer(std::move(f)); },
      "callable(iteration, position_error, orientation_error, q) called for every iterate, or "
      "None; reading gives whether one is set");

  py::class_<PositionIkOptions, LocalIkSettings> position_options(m, "PositionIkOptions");
  position_options.def(py::init<>());
  def_fields(position_options);
  py::class_<PositionIk>(m, "PositionIk",
                         "Position-only damped least squares with centre pull and limit "
                         "repulsion. solve() releases the GIL.")
      .def(py::init<const Chain&, const PositionIkOptions&>(), py::arg("chain"),
           py::arg("options") = PositionIkOptions{})
      .def_property_readonly("chain", &PositionIk::chain, "the chain solved for")
      .def_property_readonly("options", &PositionIk::options, "the solver's options")
      .def(
          "set_fixed_qpos",
          [](PositionIk& ik, py::handle q) {
            ik.set_fixed_qpos(to_vector(q, "qpos", ik.chain().robot().nq()));
          },
          py::arg("qpos"))
      .def(
          "solve",
          [](PositionIk& ik, py::handle p, py::handle seed) {
            const Eigen::Vector3d target = to_fixed<3>(p, "p_WT");
            const Eigen::VectorXd q = seed_of(ik.chain(), seed);
            return solve_released([&] { return ik.solve(target, q); });
          },
          py::arg("p_WT"), py::arg("q_seed"), "Moves the frame origin to p_WT (3,) [m].")
      .def(
          "solve_batch",
          [](PositionIk& ik, py::handle targets, py::handle seed) {
            const Eigen::MatrixXd P = to_matrix(targets, "p_WT", -1, 3);
            std::vector<Eigen::Vector3d> points;
            for (Eigen::Index i = 0; i < P.rows(); ++i) points.emplace_back(P.row(i).transpose());
            return solve_each(ik, points, seed_of(ik.chain(), seed));
          },
          py::arg("p_WT"), py::arg("q_seed"),
          "One solve per row of p_WT (k, 3) from the same seed, without the GIL.");

  py::class_<PoseIkOptions, LocalIkSettings> pose_options(m, "PoseIkOptions");
  pose_options.def(py::init<>());
  def_fields(pose_options);
  py::class_<PoseIk>(m, "PoseIk",
                     "Full-pose closed-loop IK on the SE(3) log error. solve() releases the GIL.")
      .def(py::init<const Chain&, const PoseIkOptions&>(), py::arg("chain"),
           py::arg("options") = PoseIkOptions{})
      .def_property_readonly("chain", &PoseIk::chain, "the chain solved for")
      .def_property_readonly("options", &PoseIk::options, "the solver's options")
      .def(
          "set_fixed_qpos",
          [](PoseIk& ik, py::handle q) {
            ik.set_fixed_qpos(to_vector(q, "qpos", ik.chain().robot().nq()));
          },
          py::arg("qpos"))
      .def(
          "solve",
          [](PoseIk& ik, py::handle X, py::handle seed) {
            const Pose target = to_pose(X, "X_WT");
            const Eigen::VectorXd q = seed_of(ik.chain(), seed);
            return solve_released([&] { return ik.solve(target, q); });
          },
          py::arg("X_WT"), py::arg("q_seed"))
      .def(
          "solve_batch",
          [](PoseIk& ik, const std::vector<py::object>& targets, py::handle seed) {
            return solve_each(ik, poses_of(targets), seed_of(ik.chain(), seed));
          },
          py::arg("X_WT"), py::arg("q_seed"),
          "One solve per pose in the list from the same seed, without the GIL.");

  def_enum<TargetKind>(m, "TargetKind");
  py::class_<FrameTarget>(m, "FrameTarget", "A target for one frame of a multi-target solve.")
      .def(py::init([](std::string frame, TargetKind kind, py::handle X, double wp, double wo,
                       int priority) {
             return FrameTarget{std::move(frame), kind, to_pose(X, "X_WT"), wp, wo, priority};
           }),
           py::arg("frame"), py::arg("kind") = TargetKind::pose, py::arg("X_WT") = Pose(),
           py::arg("position_weight") = 1.0, py::arg("orientation_weight") = 1.0,
           py::arg("priority") = 0)
      .def_readwrite("frame", &FrameTarget::frame, "site or body name")
      .def_readwrite("kind", &FrameTarget::kind, "what is constrained: position or pose")
      .def_readwrite("X_WT", &FrameTarget::X_WT,
                     "target pose in W (position targets use X_WT.p only)")
      .def_readwrite("position_weight", &FrameTarget::position_weight,
                     "row weight of the position error (> 0)")
      .def_readwrite("orientation_weight", &FrameTarget::orientation_weight,
                     "row weight of the orientation error (> 0, pose only)")
      .def_readwrite("priority", &FrameTarget::priority,
                     "0 is the most important; equal priorities are stacked");
  def_enum<MultiTargetMode>(m, "MultiTargetMode");
  py::class_<MultiTargetIkOptions, LocalIkSettings> multi_options(m, "MultiTargetIkOptions");
  multi_options.def(py::init<>());
  def_fields(multi_options);
  py::class_<MultiTargetIk>(m, "MultiTargetIk", "Several frames at once, with strict priorities.")
      .def(py::init<const Robot&, const std::vector<std::string>&, const std::vector<FrameTarget>&,
                    const MultiTargetIkOptions&>(),
           py::arg("robot"), py::arg("joints"), py::arg("targets"),
           py::arg("options") = MultiTargetIkOptions{})
      .def_property_readonly("chain", &MultiTargetIk::chain,
                             "the shared joints (with the first target's frame)")
      .def_property_readonly("target_count", &MultiTargetIk::target_count, "number of targets")
      .def("target", &MultiTargetIk::target, py::arg("i"))
      .def(
          "set_target",
          [](MultiTargetIk& ik, int i, py::handle X) { ik.set_target(i, to_pose(X, "X_WT")); },
          py::arg("i"), py::arg("X_WT"))
      .def(
          "set_fixed_qpos",
          [](MultiTargetIk& ik, py::handle q) {
            ik.set_fixed_qpos(to_vector(q, "qpos", ik.chain().robot().nq()));
          },
          py::arg("qpos"))
      .def(
          "solve",
          [](MultiTargetIk& ik, py::handle seed) {
            const Eigen::VectorXd q = seed_of(ik.chain(), seed);
            return solve_released([&] { return ik.solve(q); });
          },
          py::arg("q_seed"))
      .def(
          "target_errors",
          [](const MultiTargetIk& ik, int i) {
            const FrameErrors& e = ik.target_errors(i);
            return py::make_tuple(e.position, e.orientation);
          },
          py::arg("i"), "(position [m], orientation [rad]) of target i after the last solve");

  auto diff_options = py::class_<DiffIkOptions>(m, "DiffIkOptions");
  diff_options.def(py::init<>());
  def_fields(diff_options);
  def_enum<DiffIkTaskKind>(m, "DiffIkTaskKind");
  py::class_<DiffIkStep>(m, "DiffIkStep")
      .def_readonly("v", &DiffIkStep::v, "joint velocity (n,)")
      .def_readonly("q_next", &DiffIkStep::q_next, "q + v dt clipped into the limits (n,)")
      .def_property_readonly(
          "qp_status", [](const DiffIkStep& s) { return static_cast<int>(s.qp_status); },
          "status of the box QP (solved in practice)")
      .def_readonly("qp_iterations", &DiffIkStep::qp_iterations, "iterations of the box QP solver")
      .def_readonly("pulled_back", &DiffIkStep::pulled_back,
                    "a joint was outside its limits by more than one step can undo");
  auto avoidance_options = py::class_<CollisionAvoidanceOptions>(m, "CollisionAvoidanceOptions");
  avoidance_options.def(py::init<>());
  def_fields(avoidance_options);
  auto limit_options = py::class_<ConfigurationLimitOptions>(m, "ConfigurationLimitOptions");
  limit_options.def(py::init<>());
  def_fields(limit_options);
  auto barrier_options =
      py::class_<ManipulabilityBarrierOptions>(m, "ManipulabilityBarrierOptions");
  barrier_options.def(py::init<>());
  def_fields(barrier_options);
  // constraints are made by DiffIk.add_*, which owns them; Python holds references
  py::class_<DiffIkConstraint>(m, "DiffIkConstraint", "An inequality of a differential-IK QP.")
      .def_property_readonly("max_rows", &DiffIkConstraint::max_rows, "general rows it may add");
  py::class_<CollisionAvoidance, DiffIkConstraint>(
      m, "CollisionAvoidance", "Geom pairs kept apart (rows from MuJoCo's distances).")
      .def_property_readonly("options", &CollisionAvoidance::options, "the pairs and distances")
      .def_property_readonly("pair_count", &CollisionAvoidance::pair_count, "geom pairs watched")
      .def("pair", &CollisionAvoidance::pair, py::arg("i"), "(geom id, geom id) of pair i")
      .def_property_readonly("min_distance_seen", &CollisionAvoidance::min_distance_seen,
                             "smallest signed distance of any pair at any step so far [m]");
  py::class_<ConfigurationLimit, DiffIkConstraint>(
      m, "ConfigurationLimit", "A margin kept from every joint limit (a tighter box).")
      .def_property_readonly("options", &ConfigurationLimit::options, "the margin and gain");
  py::class_<ManipulabilityBarrier, DiffIkConstraint>(
      m, "ManipulabilityBarrier", "Manipulability kept above a floor (one row).")
      .def_property_readonly("options", &ManipulabilityBarrier::options, "the floor and gain")
      .def_property_readonly("manipulability", &ManipulabilityBarrier::manipulability,
                             "w at the last step's q");
  py::class_<DiffIk>(m, "DiffIk", "Differential IK as a QP with exact joint and velocity limits.")
      .def(py::init<const Chain&, const DiffIkOptions&>(), py::arg("chain"),
           py::arg("options") = DiffIkOptions{})
      .def("add_collision_avoidance",
           &add_constraint<CollisionAvoidance, CollisionAvoidanceOptions>, py::arg("options"),
           py::return_value_policy::reference_internal,
           "Keeps the options' geom pairs apart; returns the constraint (owned by this DiffIk).")
      .def("add_configuration_limit",
           &add_constraint<ConfigurationLimit, ConfigurationLimitOptions>, py::arg("options"),
           py::return_value_policy::reference_internal,
           "Keeps a margin from every joint limit; returns the constraint.")
      .def("add_manipulability_barrier",
           &add_constraint<ManipulabilityBarrier, ManipulabilityBarrierOptions>, py::arg("options"),
           py::return_value_policy::reference_internal,
           "Keeps the manipulability above a floor; returns the constraint.")
      .def_property_readonly("constraint_count", &DiffIk::constraint_count, "constraints added")
      .def("constraint", &DiffIk::constraint, py::arg("index"),
           py::return_value_policy::reference_internal)
      .def_property_readonly(
          "constraint_matrix",
          [](const DiffIk& ik) { return Eigen::MatrixXd(ik.constraint_matrix()); },
          "C (m, n) of the last step: the QP held C v >= b (unused rows zero)")
      .def_property_readonly(
          "constraint_lower",
          [](const DiffIk& ik) { return Eigen::VectorXd(ik.constraint_lower()); },
          "b (m,) of the last step (unused rows -inf)")
      .def(py::init<const Chain&, const DiffIkOptions&>(), py::arg("chain"),
           py::arg("options") = DiffIkOptions{})
      .def_property_readonly("chain", &DiffIk::chain, "the chain the tasks move")
      .def("add_pose_task", &DiffIk::add_pose_task, py::arg("frame") = "",
           py::arg("position_weight") = 1.0, py::arg("orientation_weight") = 1.0,
           py::arg("gain") = 1.0)
      .def("add_position_task", &DiffIk::add_position_task, py::arg("frame") = "",
           py::arg("weight") = 1.0, py::arg("gain") = 1.0)
      .def(
          "add_posture_task",
          [](DiffIk& ik, py::handle q, double w, double g) {
            return ik.add_posture_task(to_vector(q, "q_ref", ik.chain().size()), w, g);
          },
          py::arg("q_ref"), py::arg("weight") = 1e-3, py::arg("gain") = 1.0)
      .def(
          "set_target",
          [](DiffIk& ik, int task, py::handle target) {
            if (py::isinstance<Pose>(target)) {
              ik.set_target(task, target.cast<Pose>());
            } else if (py::isinstance<py::array>(target) &&
                       py::reinterpret_borrow<py::array>(target).ndim() == 2) {
              ik.set_target(task, to_pose(target, "target"));
            } else {
              ik.set_target(task, Eigen::Vector3d(to_fixed<3>(target, "target")));
            }
          },
          py::arg("task"), py::arg("target"), "a Pose (or 4x4), or a position (3,)")
      .def(
          "set_posture",
          [](DiffIk& ik, int task, py::handle q) {
            ik.set_posture(task, to_vector(q, "q_ref", ik.chain().size()));
          },
          py::arg("task"), py::arg("q_ref"))
      .def("set_weight", &DiffIk::set_weight, py::arg("task"), py::arg("weight"))
      .def_property_readonly("task_count", &DiffIk::task_count, "number of tasks added")
      .def("task_kind", &DiffIk::task_kind, py::arg("task"))
      .def(
          "task_error", [](const DiffIk& ik, int t) { return Eigen::VectorXd(ik.task_error(t)); },
          py::arg("task"))
      .def(
          "step",
          [](DiffIk& ik, py::handle q) { return ik.step(to_vector(q, "q", ik.chain().size())); },
          py::arg("q"), "One QP step from q (n,): DiffIkStep (v, q_next).");

  def_enum<GlobalIkMode>(m, "GlobalIkMode");
  def_enum<GlobalIkMethods>(m, "GlobalIkMethods");
  auto tolerance = py::class_<PoseTolerance>(m, "PoseTolerance", "Per-component bounds (TRAC-IK).");
  tolerance.def(py::init<>()).def_static("uniform", &PoseTolerance::uniform, py::arg("value"));
  fixed_property<PoseTolerance>(tolerance, "bound", &PoseTolerance::bound,
                                "[x, y, z] m then rotation-vector components rad (6,)");
  py::class_<GlobalIkOptions> global_options(m, "GlobalIkOptions");
  global_options.def(py::init<>())
      .def_property(
          "timeout", [](const GlobalIkOptions& o) { return o.timeout.count(); },
          [](GlobalIkOptions& o, double s) { o.timeout = std::chrono::duration<double>(s); },
          "wall-clock budget of one solve [s]")
      .def_readwrite("tolerance", &GlobalIkOptions::tolerance,
                     "acceptance test of a solution (default: 1e-5 on each component)");
  def_fields(global_options);
  py::class_<GlobalIkStats>(m, "GlobalIkStats")
      .def_readonly("attempts", &GlobalIkStats::attempts, "local runs started (1 + restarts)")
      .def_readonly("solutions", &GlobalIkStats::solutions, "attempts that met the tolerance")
      .def_readonly("lm_solutions", &GlobalIkStats::lm_solutions,
                    "solutions found by Levenberg–Marquardt")
      .def_readonly("sqp_solutions", &GlobalIkStats::sqp_solutions,
                    "solutions found by the SQP method")
      .def_readonly("manipulability", &GlobalIkStats::manipulability,
                    "√det(J·Jᵀ) at the returned q (0 without a solution)")
      .def_readonly("elapsed", &GlobalIkStats::elapsed, "wall-clock time of the solve [s]");
  py::class_<GlobalIk>(m, "GlobalIk",
                       "Random restarts of local methods within a time budget "
                       "(GIL released during solves).")
      .def(py::init<const Chain&, const GlobalIkOptions&>(), py::arg("chain"),
           py::arg("options") = GlobalIkOptions{})
      .def_property_readonly("chain", &GlobalIk::chain, "the chain solved for")
      .def_property("options", &GlobalIk::options, &GlobalIk::set_options,
                    "the options the solver was built with")
      .def(
          "set_fixed_qpos",
          [](GlobalIk& ik, py::handle q) {
            ik.set_fixed_qpos(to_vector(q, "qpos", ik.chain().robot().nq()));
          },
          py::arg("qpos"))
      .def(
          "solve",
          [](GlobalIk& ik, py::handle X, py::handle seed) {
            const Pose target = to_pose(X, "X_WT");
            const Eigen::VectorXd q = seed_of(ik.chain(), seed);
            return solve_released([&] { return ik.solve(target, q); });
          },
          py::arg("X_WT"), py::arg("q_seed"))
      .def(
          "solve_position",
          [](GlobalIk& ik, py::handle p, py::handle seed) {
            const Eigen::Vector3d target = to_fixed<3>(p, "p_WT");
            const Eigen::VectorXd q = seed_of(ik.chain(), seed);
            return solve_released([&] { return ik.solve_position(target, q); });
          },
          py::arg("p_WT"), py::arg("q_seed"))
      .def(
          "solve_batch",
          [](GlobalIk& ik, const std::vector<py::object>& targets, py::handle seed) {
            return solve_each(ik, poses_of(targets), seed_of(ik.chain(), seed));
          },
          py::arg("X_WT"), py::arg("q_seed"), "One solve per pose, without the GIL.")
      .def_property_readonly("stats", &GlobalIk::stats, "diagnostics of the last solve");

  auto analytic_options = py::class_<AnalyticIkOptions>(m, "AnalyticIkOptions");
  analytic_options.def(py::init<>());
  def_fields(analytic_options);
  def_enum<AnalyticIkFamily>(m, "AnalyticIkFamily");
  def_enum<AnalyticIkStatus>(m, "AnalyticIkStatus");
  py::class_<AnalyticIkStructure>(m, "AnalyticIkStructure", "What analyze_analytic_ik found.")
      .def_readonly("solvable", &AnalyticIkStructure::solvable, "the chain has a closed form")
      .def_readonly("family", &AnalyticIkStructure::family, "valid when solvable")
      .def_readonly("reason", &AnalyticIkStructure::reason, "why not (empty when solvable)");
  m.def("analyze_analytic_ik", &analyze_analytic_ik, py::arg("chain"),
        py::arg("options") = AnalyticIkOptions{},
        "Whether a chain has a closed-form IK, and which family (never raises for a chain).");
  py::class_<AnalyticIkBranch>(m, "AnalyticIkBranch", "One solution branch.")
      .def_readonly("q", &AnalyticIkBranch::q, "joint values (6,), wrapped into the limits")
      .def_readonly("within_limits", &AnalyticIkBranch::within_limits, "all six within limits")
      .def_readonly("singular", &AnalyticIkBranch::singular, "at a singular configuration")
      .def_readonly("position_error", &AnalyticIkBranch::position_error,
                    "miss of its forward kinematics [m] (NaN unchecked)")
      .def_readonly("orientation_error", &AnalyticIkBranch::orientation_error,
                    "rotation miss of its forward kinematics [rad]");
  py::class_<AnalyticIkSolution>(m, "AnalyticIkSolution", "Every branch of one solve.")
      .def_readonly("status", &AnalyticIkSolution::status, "solved, or why not")
      .def_readonly("dropped", &AnalyticIkSolution::dropped,
                    "branches that failed the forward-kinematics check")
      .def_property_readonly(
          "branches",
          [](const AnalyticIkSolution& s) {
            return std::vector<AnalyticIkBranch>(s.branches.begin(), s.branches.begin() + s.count);
          },
          "the branches found (up to 8)")
      .def("__len__", [](const AnalyticIkSolution& s) { return s.count; });
  py::class_<AnalyticIk>(m, "AnalyticIk", "Closed-form IK of a 6R chain: every branch.")
      .def(py::init<const Chain&, const AnalyticIkOptions&>(), py::arg("chain"),
           py::arg("options") = AnalyticIkOptions{})
      .def_property_readonly("chain", &AnalyticIk::chain, "the chain solved for")
      .def_property_readonly("options", &AnalyticIk::options, "its tolerances")
      .def_property_readonly("family", &AnalyticIk::family, "the structure recognised")
      .def(
          "solve", [](const AnalyticIk& ik, py::handle X) { return ik.solve(to_pose(X, "X_WT")); },
          py::arg("X_WT"), "Every branch reaching the pose (a Pose or 4x4).")
      .def(
          "closest_to",
          [](const AnalyticIk& ik, const AnalyticIkSolution& s, py::handle seed,
             bool within_limits_only) -> py::object {
            Eigen::VectorXd q(6);
            const int k = ik.closest_to(s, to_vector(seed, "seed", 6), q, within_limits_only);
            if (k < 0) return py::none();
            return py::make_tuple(k, q);
          },
          py::arg("solution"), py::arg("seed"), py::arg("within_limits_only") = true,
          "(branch index, q shifted by 2 pi nearest the seed), or None")
      .def(
          "forward",
          [](const AnalyticIk& ik, py::handle q) { return ik.forward(to_fixed<6>(q, "q")); },
          py::arg("q"), "The pose by the product of exponentials.");
}

}  // namespace mjarm::python
