// tasks room, docking: the scene, the controllers by law and force source, the motion, one run,
// the grid of offsets, the free-space tracking gate, their metrics. docs/docking.md.
#include <exception>
#include <memory>

#include "controller_step.hpp"
#include "declared_fields.hpp"
#include "mjarm/tasks/docking/docking.hpp"
#include "mjarm/tasks/docking/grid.hpp"
#include "mjarm/tasks/docking/tracking_gate.hpp"
#include "spec_support.hpp"

namespace mjarm::python {
namespace {

ForceSource force_source(const std::string& name) {
  return parse_enum<ForceSource>(name, "force source");
}

/// A (N, k) float64 array, row i filled by @p row(i, pointer to k values).
template <typename Row>
py::array_t<double> rows(std::size_t n, py::ssize_t k, Row row) {
  py::array_t<double> a({static_cast<py::ssize_t>(n), k});
  double* out = a.mutable_data();
  for (std::size_t i = 0; i < n; ++i) row(i, out + static_cast<py::ssize_t>(i) * k);
  return a;
}

/// Every tick's sample as arrays: {name: (N,) or (N, k)}.
py::dict sample_arrays(const std::vector<DockingSample>& s) {
  const std::size_t n = s.size();
  const auto copy = [](const auto& v, double* out) {
    for (Eigen::Index j = 0; j < v.size(); ++j) out[j] = v[j];
  };
  py::dict d;
  d["t"] = rows(n, 1, [&](std::size_t i, double* o) { o[0] = s[i].t; }).reshape({n});
  d["p_WE"] = rows(n, 3, [&](std::size_t i, double* o) { copy(s[i].X_WE.p, o); });
  d["R_WE"] = rows(n, 9, [&](std::size_t i, double* o) {
                for (int r = 0; r < 3; ++r)
                  for (int c = 0; c < 3; ++c) o[3 * r + c] = s[i].X_WE.R(r, c);
              }).reshape({static_cast<py::ssize_t>(n), py::ssize_t{3}, py::ssize_t{3}});
  d["V_WE"] = rows(n, 6, [&](std::size_t i, double* o) { copy(s[i].V_WE, o); });
  d["p_WD"] = rows(n, 3, [&](std::size_t i, double* o) { copy(s[i].X_WD.p, o); });
  d["F_peg"] = rows(n, 6, [&](std::size_t i, double* o) { copy(s[i].F_peg, o); });
  d["F_measured"] = rows(n, 6, [&](std::size_t i, double* o) { copy(s[i].F_measured, o); });
  d["stiffness"] = rows(n, 6, [&](std::size_t i, double* o) { copy(s[i].stiffness, o); });
  d["joint_position_ratio"] =
      rows(n, 1, [&](std::size_t i, double* o) { o[0] = s[i].joint_position_ratio; }).reshape({n});
  d["joint_velocity_ratio"] =
      rows(n, 1, [&](std::size_t i, double* o) { o[0] = s[i].joint_velocity_ratio; }).reshape({n});
  d["manipulability"] =
      rows(n, 1, [&](std::size_t i, double* o) { o[0] = s[i].manipulability; }).reshape({n});
  py::array_t<int> contacts(static_cast<py::ssize_t>(n));
  py::array_t<bool> saturated(static_cast<py::ssize_t>(n)), other(static_cast<py::ssize_t>(n));
  py::array_t<bool> within(static_cast<py::ssize_t>(n)), finite(static_cast<py::ssize_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<py::ssize_t>(i);
    contacts.mutable_at(k) = s[i].contacts;
    saturated.mutable_at(k) = s[i].saturated;
    other.mutable_at(k) = s[i].other_contact;
    within.mutable_at(k) = s[i].within_limits;
    finite.mutable_at(k) = s[i].finite;
  }
  d["contacts"] = contacts;
  d["saturated"] = saturated;
  d["other_contact"] = other;
  d["within_limits"] = within;
  d["finite"] = finite;
  return d;
}

void bind_scene_and_controller(py::module_& m) {
  auto geometry = py::class_<DockingGeometry>(m, "DockingGeometry",
                                              "Sizes [m] and contact settings of peg and socket.");
  fields_init<DockingGeometry>(geometry, "DockingGeometry");
  def_fields(geometry);
  array_property<DockingGeometry>(geometry, "solref", &DockingGeometry::solref,
                                  "time constant [s], damping ratio (2,)");
  array_property<DockingGeometry>(geometry, "solimp", &DockingGeometry::solimp,
                                  "dmin, dmax, width [m] (3,)");
  auto scene_options =
      py::class_<DockingSceneOptions>(m, "DockingSceneOptions", "How to build the docking scene.");
  fields_init<DockingSceneOptions>(scene_options, "DockingSceneOptions");
  scene_options
      .def_readwrite("geometry", &DockingSceneOptions::geometry, "peg and socket dimensions")
      .def_property(
          "X_WS", [](const DockingSceneOptions& o) { return o.X_WS; },
          [](DockingSceneOptions& o, py::handle X) { o.X_WS = to_pose(X, "X_WS"); },
          "pose of the socket frame S (z out of the hole)")
      .def_readwrite("ft_sensor", &DockingSceneOptions::ft_sensor, "F/T sensor pair at the flange")
      .def_readwrite("joint_friction", &DockingSceneOptions::joint_friction,
                     "Franka joint friction on joints 1-7");
  py::class_<DockingScene, std::shared_ptr<DockingScene>>(
      m, "DockingScene",
      "The compiled docking scene (iiwa14 torque motors, peg, socket); immutable, shared by "
      "runs through DockingOptions.scene.")
      .def_readonly("robot", &DockingScene::robot, "the scene's model")
      .def_readonly("chain", &DockingScene::chain, "iiwa joints 1-7, frame: the peg tip")
      .def_readonly("options", &DockingScene::options, "the options the scene was built with")
      .def_readonly("peg", &DockingScene::peg, "the peg's geoms")
      .def_readonly("socket", &DockingScene::socket, "the socket's geoms")
      .def_readonly("peg_body", &DockingScene::peg_body, "body id of the peg")
      .def_readonly("peg_mass", &DockingScene::peg_mass, "the peg's mass [kg]")
      .def_property_readonly(
          "peg_com_E", [](const DockingScene& s) { return Eigen::Vector3d(s.peg_com_E); },
          "the peg's centre of mass in E (3,) [m]")
      .def("seated", py::overload_cast<>(&DockingScene::seated, py::const_),
           "Pose of the tip seated at the bottom of the hole.");
  m.def(
      "build_docking_scene",
      [](const DockingSceneOptions& o) {
        py::gil_scoped_release release;
        return std::make_shared<DockingScene>(build_docking_scene(o));
      },
      py::arg("options") = DockingSceneOptions{},
      "Composes and compiles the docking scene (GIL released).");
  m.def("docking_scene", &docking_scene, py::arg("options") = DockingSceneOptions{},
        "The docking scene's parts as a Scene, not compiled.");

  py::enum_<DockingLaw>(m, "DockingLaw", "The control laws the docking compares.")
      .value("cic", DockingLaw::cic)
      .value("hqp_ac", DockingLaw::hqp_ac)
      .value("se3", DockingLaw::se3);
  def_enum<ForceSource>(m, "ForceSource", "Where the measured wrench comes from.");
  auto co = py::class_<DockingControllerOptions>(
      m, "DockingControllerOptions",
      "Law, force source and gains ([x, y, z, rx, ry, rz]; E's axes for se3, world for cic and "
      "hqp-ac). docs/docking.md has the tuned values.");
  fields_init<DockingControllerOptions>(co, "DockingControllerOptions");
  def_fields(co);
  // the enum fields also take their names
  enum_property<DockingControllerOptions>(
      co, "law", &DockingControllerOptions::law,
      [](const std::string& s) { return docking_law(s); }, "DockingLaw or 'cic', 'hqp-ac', 'se3'");
  enum_property<DockingControllerOptions>(co, "source", &DockingControllerOptions::source,
                                          &force_source, "ForceSource or 'sensor', 'observer'");
  co.def_readwrite("release_axes", &DockingControllerOptions::release_axes,
                   "released on contact, E's [x, y, z, rx, ry, rz] (6 bools)")
      .def_readwrite("friction_mode", &DockingControllerOptions::friction_mode,
                     "what gives the friction feed-forward its sign: the joint velocity or the "
                     "commanded torque");

  auto docking =
      py::class_<DockingController, Controller>(
          m, "DockingController",
          "A docking law with its force source (torque mode); usable in a Simulation like any "
          "controller.")
          .def(py::init<const DockingScene&, const DockingControllerOptions&>(), py::arg("scene"),
               py::arg("options") = DockingControllerOptions{})
          .def_property_readonly("options", &DockingController::options,
                                 "the options the controller was built with")
          .def_property_readonly(
              "measured_wrench",
              [](const DockingController& c) { return Vector6d(c.measured_wrench()); },
              "wrench on E at the last compute, world axes (6,) [N; N m]")
          .def_property_readonly(
              "stiffness", [](const DockingController& c) { return Vector6d(c.stiffness()); },
              "stiffness diagonal in force at the last compute (6,)")
          .def_property_readonly("bad_wrench_ticks", &DockingController::bad_wrench_ticks,
                                 "ticks whose sensor reading was not finite (taken as zero, or the "
                                 "last good value for se3)");
  bind_compute<DockingController>(docking);
}

void bind_motion(py::module_& m) {
  auto offset = py::class_<DockingOffset>(
      m, "DockingOffset",
      "Error of the believed socket pose, in the socket's frame: dx, dy [m], dyaw [rad].");
  offset
      .def(py::init([](double dx, double dy, double dyaw) {
             return DockingOffset{dx, dy, dyaw};
           }),
           py::arg("dx") = 0.0, py::arg("dy") = 0.0, py::arg("dyaw") = 0.0)
      .def_readwrite("dx", &DockingOffset::dx,
                     "error of the believed socket along x, |dx| ≤ 0.05 [m]")
      .def_readwrite("dy", &DockingOffset::dy,
                     "error of the believed socket along y, |dy| ≤ 0.05 [m]")
      .def_readwrite("dyaw", &DockingOffset::dyaw,
                     "error of the believed socket about its axis, |dyaw| ≤ π [rad]");
  py::enum_<DockingReference>(m, "DockingReference", "The shape of the reference.")
      .value("two_phase", DockingReference::two_phase)
      .value("single_segment", DockingReference::single_segment);
  def_enum<SearchPattern>(m, "SearchPattern", "The docking's planar search pattern.");
  auto search = py::class_<DockingSearchOptions>(
      m, "DockingSearchOptions", "Miss detection and the search for the hole (docs/docking.md).");
  fields_init<DockingSearchOptions>(search, "DockingSearchOptions");
  def_fields(search);
  auto centring = py::class_<DockingCentringOptions>(
      m, "DockingCentringOptions",
      "Centring in the bore from the contact excursion (docs/docking.md).");
  fields_init<DockingCentringOptions>(centring, "DockingCentringOptions");
  def_fields(centring);
  auto motion = py::class_<DockingMotion>(m, "DockingMotion",
                                          "Timing [s] and sizes [m] of the motion, the preload.");
  fields_init<DockingMotion>(motion, "DockingMotion");
  def_fields(motion);
  // the enum field also takes its names
  enum_property<DockingMotion>(
      motion, "reference", &DockingMotion::reference,
      [](const std::string& s) { return docking_reference(s); },
      "DockingReference or 'two-phase', 'single'");
  auto criteria = py::class_<DockingCriteria>(m, "DockingCriteria",
                                              "Seating criteria (final window and whole run).");
  fields_init<DockingCriteria>(criteria, "DockingCriteria");
  def_fields(criteria);
  py::class_<DockingPlan>(m, "DockingPlan", "Everything fixed before a run (poses in world).")
      .def_readonly("offset", &DockingPlan::offset,
                    "how the believed socket differs from the true one")
      .def_readonly("X_WS", &DockingPlan::X_WS, "the true socket")
      .def_readonly("X_WB", &DockingPlan::X_WB, "the believed socket")
      .def_readonly("X_start", &DockingPlan::X_start,
                    "E at the start: above the true socket by start_height, peg down")
      .def_readonly("X_standoff", &DockingPlan::X_standoff,
                    "E above the believed socket by the standoff")
      .def_readonly("X_seated", &DockingPlan::X_seated, "in the believed socket")
      .def_property_readonly(
          "q_start", [](const DockingPlan& p) { return Eigen::VectorXd(p.q_start); },
          "the arm at X_start, IK from the home keyframe (7,) [rad]")
      .def_readonly("full_depth", &DockingPlan::full_depth, "chamfer + bore depth [m]")
      .def_readonly("approach_time", &DockingPlan::approach_time,
                    "duration of the approach to the standoff [s]")
      .def_readonly("insert_time", &DockingPlan::insert_time,
                    "duration of the insertion (0 for single-segment) [s]")
      .def_readonly("hold_time", &DockingPlan::hold_time, "duration of the hold at the end [s]")
      .def("duration", &DockingPlan::duration, "[s]");
  m.def(
      "plan_docking",
      [](const DockingScene& scene, const DockingOffset& offset, const DockingMotion& motion) {
        return plan_docking(scene, offset, motion);
      },
      py::arg("scene"), py::arg("offset") = DockingOffset{}, py::arg("motion") = DockingMotion{},
      "The plan of a run: poses, the start configuration by IK, durations.");
}

void bind_docking_results(py::module_& m) {
  auto metrics =
      py::class_<DockingMetrics>(
          m, "DockingMetrics",
          "Metrics of one run: whole run, final window, verdict. Forces [N], "
          "moments [N m], lengths [m], angles [rad].")
          // the names before the declaration (the JSON's) took the percent
          .def_property_readonly(
              "max_joint_position", [](const DockingMetrics& d) { return d.max_joint_position; },
              "alias of max_joint_position_percent")
          .def_property_readonly(
              "max_joint_velocity", [](const DockingMetrics& d) { return d.max_joint_velocity; },
              "alias of max_joint_velocity_percent");
  def_readonly_fields(metrics);
  def_enum<DockingOutcome>(m, "DockingOutcome", "How a docking run ended.");
  py::class_<DockingReport>(m, "DockingReport", "What a docking run did.")
      .def_readonly("plan", &DockingReport::plan,
                    "the approach planned: offset, start and standoff poses")
      .def_readonly("controller", &DockingReport::controller, "'cic', 'hqp-ac', 'se3'")
      .def_readonly("source", &DockingReport::source, "where the measured wrench came from")
      .def_readonly("joint_friction", &DockingReport::joint_friction,
                    "the variant with Franka joint friction")
      .def_readonly("run", &DockingReport::run,
                    "the simulation's account (status, end time, message)")
      .def_readonly("metrics", &DockingReport::metrics, "forces, depths and times of the run")
      .def_readonly("outcome", &DockingReport::outcome,
                    "seated, not seated, or why the run stopped")
      .def_readonly("control_period", &DockingReport::control_period,
                    "control period of the run [s]")
      .def_readonly("bad_wrench_ticks", &DockingReport::bad_wrench_ticks,
                    "non-finite sensor readings (taken as zero)")
      .def_readonly(
          "qp_least_squares", &DockingReport::qp_least_squares,
          "hqp-ac: ticks whose main QP failed (least-squares fallback); 0 for the other laws")
      .def_readonly(
          "qp_null_space_dropped", &DockingReport::qp_null_space_dropped,
          "hqp-ac: ticks whose null-space QP failed (its step dropped); 0 for the other laws")
      .def_property_readonly(
          "sample_count", [](const DockingReport& r) { return r.samples.size(); },
          "number of ticks sampled (0 when samples were not kept)")
      .def(
          "samples", [](const DockingReport& r) { return sample_arrays(r.samples); },
          "Every tick's ground truth as arrays (N = sample_count; empty without keep_samples): "
          "t (N,), p_WE (N, 3), R_WE (N, 3, 3), V_WE (N, 6), p_WD (N, 3), F_peg (N, 6), "
          "F_measured (N, 6), stiffness (N, 6), joint_position_ratio, joint_velocity_ratio, "
          "manipulability (N,), contacts (N,) int, saturated, other_contact, within_limits, "
          "finite (N,) bool.")
      .def_readonly("recording", &DockingReport::recording,
                    "the recording directory (empty when not recorded)")
      .def_readonly("recording_error", &DockingReport::recording_error,
                    "why the recording is incomplete (empty when fine)")
      .def_readonly("video", &DockingReport::video, "the MP4 asked for (empty when no video)")
      .def_readonly("video_frames", &DockingReport::video_frames, "frames written to the video")
      .def_readonly("video_error", &DockingReport::video_error,
                    "why the video was not written (empty when fine)")
      .def_readonly("video_written", &DockingReport::video_written,
                    "the MP4 is complete at its path (an old file is kept if not)")
      .def("ok", &DockingReport::ok, "True when seated")
      .def("result_line", &docking_result_line, "One line with the figures.");

  py::class_<DockingGridRun>(m, "DockingGridRun", "One run of the grid.")
      .def_readonly("offset", &DockingGridRun::offset, "the socket offset this run was given")
      .def_readonly("outcome", &DockingGridRun::outcome,
                    "seated, not seated, or why the run stopped")
      .def_readonly("metrics", &DockingGridRun::metrics, "forces, depths and times of the run")
      .def_readonly("message", &DockingGridRun::message,
                    "the run's own account (RunResult.message)");
  py::class_<DockingGridResult>(m, "DockingGridResult",
                                "The grid's runs (x slowest, then y, then yaw) and summary.")
      .def_readonly("controller", &DockingGridResult::controller,
                    "the docking law: \"cic\", \"hqp-ac\" or \"se3\"")
      .def_readonly("source", &DockingGridResult::source, "where the measured wrench came from")
      .def_readonly("joint_friction", &DockingGridResult::joint_friction,
                    "the variant with Franka joint friction")
      .def_readonly("planned", &DockingGridResult::planned, "runs in the matrix")
      .def_readonly("interrupted", &DockingGridResult::interrupted,
                    "Ctrl-C/SIGTERM stopped the matrix: runs holds the runs that completed")
      .def_readonly("runs", &DockingGridResult::runs,
                    "the completed runs, in matrix order (x slowest, then y, then yaw)")
      .def_readonly("seated", &DockingGridResult::seated, "completed runs that seated the peg")
      .def_readonly("max_peak_force", &DockingGridResult::max_peak_force,
                    "largest peak contact force over the runs [N]")
      .def_readonly("max_peak_axial_force", &DockingGridResult::max_peak_axial_force,
                    "largest peak axial force over the runs [N]")
      .def_readonly("max_peak_axial_moment", &DockingGridResult::max_peak_axial_moment,
                    "largest peak axial moment over the runs [N·m]")
      .def_readonly("max_lateral", &DockingGridResult::max_lateral,
                    "worst final-window lateral error [m]")
      .def_readonly("max_tilt", &DockingGridResult::max_tilt, "worst final-window tilt [rad]")
      .def_readonly("min_steady_axial_force", &DockingGridResult::min_steady_axial_force,
                    "smallest final-window axial force [N]")
      .def_readonly("max_steady_axial_force", &DockingGridResult::max_steady_axial_force,
                    "largest final-window axial force [N]")
      .def_readonly("max_position_rms", &DockingGridResult::max_position_rms,
                    "worst free-motion position RMS [m]")
      .def_readonly("max_orientation_rms", &DockingGridResult::max_orientation_rms,
                    "worst free-motion orientation RMS [rad]")
      .def_readonly("failures", &DockingGridResult::failures, "reason -> runs");
}

void bind_runs(py::module_& m) {
  auto video = py::class_<DockingVideo>(m, "DockingVideo", "A video of a docking run.");
  fields_init<DockingVideo>(video, "DockingVideo");
  video.def_readwrite("path", &DockingVideo::path, "MP4; '' = none")
      .def_readwrite("camera", &DockingVideo::camera, "'' (default view), 'follow' or a camera")
      .def_readwrite("options", &DockingVideo::options,
                     "size, frame rate, encoding, render options");
  auto options = py::class_<DockingOptions>(m, "DockingOptions", "How to run one docking.");
  fields_init<DockingOptions>(options, "DockingOptions");
  options.def_readwrite("controller", &DockingOptions::controller, "law, force source, gains")
      .def_readwrite("offset", &DockingOptions::offset, "the error of the believed socket pose")
      .def_readwrite("motion", &DockingOptions::motion, "reference shape and timing, preload")
      .def_readwrite("criteria", &DockingOptions::criteria, "the seating criteria")
      .def_readwrite("joint_friction", &DockingOptions::joint_friction,
                     "the variant with Franka joint friction")
      .def_readwrite("geometry", &DockingOptions::geometry, "the peg and the socket")
      .def_property(
          "scene",
          [](const DockingOptions& o) -> std::shared_ptr<DockingScene> {
            return std::const_pointer_cast<DockingScene>(o.scene);
          },
          [](DockingOptions& o, std::shared_ptr<DockingScene> s) { o.scene = std::move(s); },
          "a compiled DockingScene shared by runs, or None: built per run")
      .def_readwrite("max_acceleration", &DockingOptions::max_acceleration,
                     "divergence bound on |q̈| [rad/s²]")
      .def_readwrite("record", &DockingOptions::record, "recording directory; '' = none")
      .def_readwrite("video", &DockingOptions::video, "MP4 of the run (empty path: none)")
      .def_readwrite("keep_samples", &DockingOptions::keep_samples, "keep every tick's sample");

  m.def(
      "run_docking",
      [](const DockingOptions& options) {
        return call_released([&] { return run_docking(options); });
      },
      py::arg("options") = DockingOptions{},
      "One peg-in-hole run (GIL released): scene, plan, simulation under the docking "
      "controller, metrics and verdict. Bad options raise mjarm.Error before the first step; "
      "Ctrl-C raises KeyboardInterrupt.");

  auto grid = py::class_<DockingGridOptions>(
      m, "DockingGridOptions",
      "The matrix of offsets (x, y [m], yaw [rad] values) and the base options of every run.");
  fields_init<DockingGridOptions>(grid, "DockingGridOptions");
  grid.def_readwrite("base", &DockingGridOptions::base,
                     "everything but the offset (DockingOptions; no record or video)");
  list_property<DockingGridOptions>(grid, "x", &DockingGridOptions::x, "dx values (n,) [m]");
  list_property<DockingGridOptions>(grid, "y", &DockingGridOptions::y, "dy values (n,) [m]");
  list_property<DockingGridOptions>(grid, "yaw", &DockingGridOptions::yaw,
                                    "dyaw values (n,) [rad]");
  grid.def_readwrite("jobs", &DockingGridOptions::jobs, "threads; 0: one per core");
  m.def(
      "run_docking_grid",
      [](const DockingGridOptions& options, const py::object& progress) {
        std::exception_ptr error;
        DockingGridProgress report;
        if (!progress.is_none()) {
          report = [&](int done, int planned) {
            py::gil_scoped_acquire gil;
            if (error) return;
            try {
              progress(done, planned);
            } catch (...) {
              error = std::current_exception();
            }
          };
        }
        DockingGridResult r = call_released([&] { return run_docking_grid(options, report); });
        if (error) std::rethrow_exception(error);
        return r;
      },
      py::arg("options") = DockingGridOptions{}, py::arg("progress") = py::none(),
      "Runs the grid in options.jobs threads sharing one scene (GIL released); progress(done, "
      "planned) is called as runs complete. Ctrl-C raises KeyboardInterrupt.");
}

void bind_gate(py::module_& m) {
  auto gate = py::class_<TrackingGateOptions>(
      m, "TrackingGateOptions",
      "The free-space tracking gate: a circle then a figure-eight in the y-z plane.");
  fields_init<TrackingGateOptions>(gate, "TrackingGateOptions");
  def_fields(gate);
  gate.def_property(
      "scene",
      [](const TrackingGateOptions& o) { return std::const_pointer_cast<DockingScene>(o.scene); },
      [](TrackingGateOptions& o, std::shared_ptr<DockingScene> s) { o.scene = std::move(s); },
      "a compiled DockingScene, or None: built");
  py::class_<TrackingErrors>(m, "TrackingErrors", "Errors over a stretch of the gate.")
      .def_readonly("samples", &TrackingErrors::samples, "ticks the errors were taken over")
      .def_readonly("position_rms", &TrackingErrors::position_rms, "RMS of ‖p_E − p_ref‖ [m]")
      .def_readonly("orientation_rms", &TrackingErrors::orientation_rms,
                    "RMS of the angle of R_refᵀ·R_E [rad]")
      .def_readonly("max_position", &TrackingErrors::max_position, "largest ‖p_E − p_ref‖ [m]")
      .def_readonly("max_orientation", &TrackingErrors::max_orientation,
                    "largest angle of R_refᵀ·R_E [rad]");
  py::class_<TrackingGateReport>(m, "TrackingGateReport", "What the gate measured.")
      .def_readonly("controller", &TrackingGateReport::controller,
                    "the docking law: \"cic\", \"hqp-ac\" or \"se3\"")
      .def_readonly("source", &TrackingGateReport::source, "where the measured wrench came from")
      .def_readonly("run", &TrackingGateReport::run, "the simulation's account")
      .def_readonly("X_start", &TrackingGateReport::X_start,
                    "the start point c with the held orientation")
      .def_readonly("loops", &TrackingGateReport::loops, "circle, figure-eight")
      .def_readonly("total", &TrackingGateReport::total,
                    "errors over both loops and the settle time")
      .def_readonly("contact_ticks", &TrackingGateReport::contact_ticks,
                    "ticks with any contact (must be 0: free space)")
      .def("ok", &TrackingGateReport::ok)
      .def(
          "passes",
          [](const TrackingGateReport& r, double position_rms, double orientation_rms) {
            return passes(r, TrackingGateTargets{position_rms, orientation_rms});
          },
          py::arg("position_rms") = TrackingGateTargets{}.position_rms,
          py::arg("orientation_rms") = TrackingGateTargets{}.orientation_rms,
          "Finished without contact and both RMS within the targets [m], [rad].");
  m.def(
      "run_tracking_gate",
      [](const TrackingGateOptions& options) {
        return call_released([&] { return run_tracking_gate(options); });
      },
      py::arg("options") = TrackingGateOptions{},
      "Runs the gate under a docking controller (GIL released).");
}

}  // namespace

void bind_docking(py::module_& m) {
  bind_scene_and_controller(m);
  bind_motion(m);
  bind_docking_results(m);
  bind_runs(m);
  bind_gate(m);
}

}  // namespace mjarm::python
