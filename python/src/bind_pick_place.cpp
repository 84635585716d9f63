// tasks room, pick and place: options, one trial, parallel trials and their summary, the scene of
// a trial, the robots it knows. docs/pick_place.md.
#include <exception>
#include <memory>
#include <mutex>

#include "declared_fields.hpp"
#include "mjarm/tasks/pick_place/pick_place.hpp"
#include "mjarm/tasks/pick_place/trials.hpp"
#include "spec_support.hpp"

namespace mjarm::python {
namespace {

/// An optional x y pair: None or a float64 array (2,).
template <typename T, typename Class>
void optional_pair(Class& cls, const char* name, std::optional<std::array<double, 2>> T::*member,
                   const char* doc) {
  cls.def_property(
      name,
      [member](const T& o) -> std::optional<Eigen::Vector2d> {
        if (!(o.*member)) return std::nullopt;
        return Eigen::Vector2d((*(o.*member))[0], (*(o.*member))[1]);
      },
      [member, name](T& o, py::handle v) {
        if (v.is_none()) {
          (o.*member).reset();
          return;
        }
        const Eigen::Vector2d x = to_fixed<2>(v, name);
        o.*member = std::array<double, 2>{x[0], x[1]};
      },
      doc);
}

void bind_pick_place_options(py::module_& m) {
  def_enum<GraspKind>(m, "GraspKind", "How the object is held.");
  py::enum_<PickPlaceState>(m, "PickPlaceState", "The 14 states of the machine, in order.")
      .value("approach", PickPlaceState::approach)
      .value("dwell_a", PickPlaceState::dwell_a)
      .value("descend", PickPlaceState::descend)
      .value("dwell_b", PickPlaceState::dwell_b)
      .value("grasp", PickPlaceState::grasp)
      .value("dwell_c", PickPlaceState::dwell_c)
      .value("lift", PickPlaceState::lift)
      .value("dwell_d", PickPlaceState::dwell_d)
      .value("move", PickPlaceState::move)
      .value("dwell_e", PickPlaceState::dwell_e)
      .value("place", PickPlaceState::place)
      .value("dwell_f", PickPlaceState::dwell_f)
      .value("release", PickPlaceState::release)
      .value("done", PickPlaceState::done);
  def_enum<PickPlaceFailure>(m, "PickPlaceFailure",
                             "Why a trial failed: the first that applies, in this order.");

  auto limits =
      py::class_<CartesianLimits>(m, "CartesianLimits", "Limits of a Cartesian trapezoid segment.");
  fields_init<CartesianLimits>(limits, "CartesianLimits");
  limits.def_readwrite("max_velocity", &CartesianLimits::max_velocity, "along the line [m/s]")
      .def_readwrite("max_acceleration", &CartesianLimits::max_acceleration,
                     "largest linear acceleration (> 0) [m/s²]")
      .def_readwrite("max_angular_velocity", &CartesianLimits::max_angular_velocity,
                     "largest angular velocity about the turn axis (> 0) [rad/s]")
      .def_readwrite("max_angular_acceleration", &CartesianLimits::max_angular_acceleration,
                     "largest angular acceleration (> 0) [rad/s²]");

  auto motion = py::class_<PickPlaceMotion>(
      m, "PickPlaceMotion",
      "Every constant of the machine (the classic defaults). Heights of the tool frame above "
      "the object's centre or above the target [m]; times [s].");
  fields_init<PickPlaceMotion>(motion, "PickPlaceMotion");
  def_fields(motion);

  auto monitor = py::class_<GraspMonitorOptions>(m, "GraspMonitorOptions",
                                                 "When a held object has slipped or is lost.");
  fields_init<GraspMonitorOptions>(monitor, "GraspMonitorOptions");
  monitor
      .def_readwrite(
          "slip_distance", &GraspMonitorOptions::slip_distance,
          "the object has slipped once it moved this far from its grasped pose (> 0) [m]")
      .def_readwrite(
          "drop_distance", &GraspMonitorOptions::drop_distance,
          "the object is lost beyond this distance from its grasped pose (> slip_distance) [m]");
  auto weld = py::class_<WeldGraspOptions>(m, "WeldGraspOptions", "The weld's solref.");
  fields_init<WeldGraspOptions>(weld, "WeldGraspOptions");
  weld.def_readwrite("time_constant", &WeldGraspOptions::time_constant,
                     "time constant of the weld's solref (> 0) [s]")
      .def_readwrite("damping_ratio", &WeldGraspOptions::damping_ratio,
                     "damping ratio of the weld constraint");

  auto criteria =
      py::class_<PickPlaceCriteria>(m, "PickPlaceCriteria", "What a trial is judged by.");
  fields_init<PickPlaceCriteria>(criteria, "PickPlaceCriteria");
  def_fields(criteria);
  criteria.def_readwrite("grasp", &PickPlaceCriteria::grasp,
                         "when the object slipped or was dropped");

  auto ranges = py::class_<PickPlaceRanges>(m, "PickPlaceRanges",
                                            "Where a seed draws a trial from (uniform, [lo, hi]).");
  fields_init<PickPlaceRanges>(ranges, "PickPlaceRanges");
  def_fields(ranges);

  auto object = py::class_<PickPlaceObject>(m, "PickPlaceObject",
                                            "The object to pick, upright on the table.");
  fields_init<PickPlaceObject>(object, "PickPlaceObject");
  object.def_readwrite("shape", &PickPlaceObject::shape, "'box' or 'cylinder'");
  list_property<PickPlaceObject>(object, "size", &PickPlaceObject::size,
                                 "box: half extents (3,); cylinder: radius, half height (2,) [m]");
  object.def_readwrite("mass", &PickPlaceObject::mass, "object mass [kg]")
      .def_readwrite("friction", &PickPlaceObject::friction, "sliding friction");
  array_property<PickPlaceObject>(object, "position", &PickPlaceObject::position,
                                  "centre on the table x, y (2,) [m]");
  object.def_readwrite("yaw", &PickPlaceObject::yaw, "rotation about the vertical [rad]");

  auto trial = py::class_<PickPlaceTrial>(m, "PickPlaceTrial", "One trial's draw.");
  fields_init<PickPlaceTrial>(trial, "PickPlaceTrial");
  trial.def_readwrite("seed", &PickPlaceTrial::seed, "the seed the trial was drawn from")
      .def_readwrite("object", &PickPlaceTrial::object,
                     "the object's size, mass, friction, position and yaw");
  array_property<PickPlaceTrial>(trial, "target", &PickPlaceTrial::target,
                                 "where the object should end, x, y (2,) [m]");

  auto video_options =
      py::class_<RunVideoOptions>(m, "RunVideoOptions", "Size and rate of a run's video.");
  fields_init<RunVideoOptions>(video_options, "RunVideoOptions");
  video_options.def_readwrite("width", &RunVideoOptions::width, "[pixels], even")
      .def_readwrite("height", &RunVideoOptions::height, "[pixels], even")
      .def_readwrite("fps", &RunVideoOptions::fps, "frames per simulated second");
  auto video = py::class_<PickPlaceVideo>(m, "PickPlaceVideo", "A video of a trial.");
  fields_init<PickPlaceVideo>(video, "PickPlaceVideo");
  video.def_readwrite("path", &PickPlaceVideo::path, "MP4 to write; '' = none")
      .def_readwrite("cameras", &PickPlaceVideo::cameras,
                     "'front', 'side', 'top', 'follow'; empty: front")
      .def_readwrite("tiled", &PickPlaceVideo::tiled, "one tiled file (else one per camera)")
      .def_readwrite("options", &PickPlaceVideo::options,
                     "size of each camera's picture, frame rate, encoding, render");

  auto options = py::class_<PickPlaceOptions>(
      m, "PickPlaceOptions",
      "How to run one pick and place: robot ('arm6', 'panda_hand'), grasp, mode, seed, fixed "
      "positions instead of drawn ones, the classic edits, motion, criteria.");
  fields_init<PickPlaceOptions>(options, "PickPlaceOptions");
  options.def_readwrite("robot", &PickPlaceOptions::robot, "'arm6' or 'panda_hand'");
  enum_property<PickPlaceOptions>(
      options, "grasp", &PickPlaceOptions::grasp,
      [](const std::string& s) { return grasp_kind(s); }, "GraspKind or 'weld' / 'friction'");
  enum_property<PickPlaceOptions>(
      options, "mode", &PickPlaceOptions::mode,
      [](const std::string& s) { return simulation_mode_named(s); },
      "SimulationMode.position (IK into servos) or .torque (operational space), or the name");
  options.def_readwrite("seed", &PickPlaceOptions::seed, "draws what is not fixed")
      .def_readwrite("ranges", &PickPlaceOptions::ranges, "the ranges trials are drawn from");
  optional_pair<PickPlaceOptions>(options, "object_position", &PickPlaceOptions::object_position,
                                  "object centre x, y (2,) [m], or None: drawn");
  optional_pair<PickPlaceOptions>(options, "target_position", &PickPlaceOptions::target_position,
                                  "target x, y (2,) [m], or None: drawn");
  options
      .def_readwrite("object_half_size", &PickPlaceOptions::object_half_size,
                     "cube half extent [m], or None: drawn")
      .def_readwrite("classic", &PickPlaceOptions::classic,
                     "7.5 mm cube, finger travel [0, 0.012] m, finger servo gain 3200")
      .def_readwrite("motion", &PickPlaceOptions::motion,
                     "the motion's timing and Cartesian limits")
      .def_readwrite("criteria", &PickPlaceOptions::criteria,
                     "when a trial succeeds, and grasp monitoring")
      .def_readwrite("weld", &PickPlaceOptions::weld, "the weld's solref (weld grasp)")
      .def_readwrite("grasp_force", &PickPlaceOptions::grasp_force, "finger squeeze [N]")
      .def_readwrite("noslip_iterations", &PickPlaceOptions::noslip_iterations,
                     "MuJoCo's noslip solver iterations (0: off)")
      .def_readwrite("impratio", &PickPlaceOptions::impratio,
                     "MuJoCo's frictional-to-normal impedance ratio (≥ 1)")
      .def_readwrite("control_period", &PickPlaceOptions::control_period, "[s]; 0 = one step")
      .def_readwrite("max_acceleration", &PickPlaceOptions::max_acceleration,
                     "divergence bound on |qdd|")
      .def_readwrite("record", &PickPlaceOptions::record, "recording directory; '' = none")
      .def_readwrite("state_decimation", &PickPlaceOptions::state_decimation,
                     "one state row every N physics steps when recording")
      .def_readwrite("video", &PickPlaceOptions::video,
                     "MP4 of one or more cameras (empty path: none)");
}

void bind_pick_place_results(py::module_& m) {
  auto trace = py::class_<PickPlaceTrace>(m, "PickPlaceTrace",
                                          "What the machine saw (NaN: did not happen).");
  def_readonly_fields(trace);

  py::class_<PickPlaceReport>(m, "PickPlaceReport", "What one trial did.")
      .def_readonly("trial", &PickPlaceReport::trial, "PickPlaceTrial: the draw")
      .def_readonly("robot", &PickPlaceReport::robot, "the robot's name")
      .def_readonly("grasp", &PickPlaceReport::grasp, "how the object was held (friction or weld)")
      .def_readonly("mode", &PickPlaceReport::mode,
                    "how the robot moved (kinematic, position or torque)")
      .def_readonly("run", &PickPlaceReport::run,
                    "the simulation's account (status, end time, message)")
      .def_readonly("trace", &PickPlaceReport::trace,
                    "grasp force, weld jump and settle, slip, table contact, saturation")
      .def_readonly("success", &PickPlaceReport::success, "the object ended at the target")
      .def_readonly("failure", &PickPlaceReport::failure, "why the trial failed (none on success)")
      .def_readonly("reason", &PickPlaceReport::reason, "one line; '' on success")
      .def_readonly("placement_error", &PickPlaceReport::placement_error, "horizontal [m]")
      .def_readonly("final_speed", &PickPlaceReport::final_speed, "object speed at the end [m/s]")
      .def_readonly("tilt", &PickPlaceReport::tilt, "object tilt at the end [rad]")
      .def_readonly("cycle_time", &PickPlaceReport::cycle_time, "time from start to DONE [s]")
      .def_readonly("control_period", &PickPlaceReport::control_period,
                    "control period of the run [s]")
      .def_readonly("recording", &PickPlaceReport::recording,
                    "the recording directory (empty when not recorded)")
      .def_readonly("recording_error", &PickPlaceReport::recording_error,
                    "why the recording is incomplete (empty when fine)")
      .def_readonly("videos", &PickPlaceReport::videos, "the MP4s asked for")
      .def_readonly("video_frames", &PickPlaceReport::video_frames, "frames written per video")
      .def_readonly("video_error", &PickPlaceReport::video_error,
                    "why a video was not written (empty when fine)")
      .def("ok", &PickPlaceReport::ok, "True on success");

  py::class_<PickPlaceStat>(m, "PickPlaceStat", "Mean and largest of a figure (NaN when none).")
      .def_readonly("count", &PickPlaceStat::count, "values added (NaN skipped)")
      .def_readonly("mean", &PickPlaceStat::mean,
                    "mean value, in the quantity's unit (NaN when none)")
      .def_readonly("max", &PickPlaceStat::max,
                    "largest value, in the quantity's unit (NaN when none)");
  py::class_<PickPlaceSummary>(m, "PickPlaceSummary", "The figures of a batch.")
      .def_readonly("trials", &PickPlaceSummary::trials, "trials that ran to their end")
      .def_readonly("successes", &PickPlaceSummary::successes,
                    "trials that ended with the object at the target")
      .def_readonly("interrupted", &PickPlaceSummary::interrupted, "cut short (not in trials)")
      .def_property_readonly(
          "failures",
          [](const PickPlaceSummary& s) {
            py::dict d;
            for (std::size_t i = 1; i < s.failures.size(); ++i)
              d[to_string(static_cast<PickPlaceFailure>(i))] = s.failures[i];
            return d;
          },
          "failures per reason: {name: count} (every reason)")
      .def_readonly("placement_error", &PickPlaceSummary::placement_error, "[m], successes")
      .def_readonly("cycle_time", &PickPlaceSummary::cycle_time, "[s], successes")
      .def_readonly("grasp_force", &PickPlaceSummary::grasp_force, "transport mean [N]")
      .def_readonly("weld_jump", &PickPlaceSummary::weld_jump,
                    "weld jump, over the trials whose weld was switched on [m]")
      .def_readonly("weld_settle", &PickPlaceSummary::weld_settle,
                    "weld settle, over the trials whose weld was switched on [m]")
      .def_readonly("max_slip", &PickPlaceSummary::max_slip,
                    "largest slip, over the trials that closed on the object [m]")
      .def("success_rate", &PickPlaceSummary::success_rate, "in [0, 1]; NaN without trials");
  py::class_<PickPlaceBatch>(m, "PickPlaceBatch", "What a batch did.")
      .def_readonly("reports", &PickPlaceBatch::reports, "list[PickPlaceReport], seed order")
      .def_readonly("summary", &PickPlaceBatch::summary, "the figures of the batch")
      .def_readonly("interrupted", &PickPlaceBatch::interrupted, "Ctrl-C stopped the batch");
}

void bind_scene_of_a_trial(py::module_& m) {
  py::class_<PickPlaceRobot>(m, "PickPlaceRobot",
                             "A robot the pick and place knows (names unprefixed, world [m]).")
      .def_readonly("name", &PickPlaceRobot::name, "what the user types (\"arm6\")")
      .def_readonly("position_model", &PickPlaceRobot::position_model,
                    "bundled model with position servos (\"arm6\")")
      .def_readonly("torque_model", &PickPlaceRobot::torque_model,
                    "bundled model with torque motors (\"arm6_torque\")")
      .def_readonly("tool", &PickPlaceRobot::tool, "tool site between the fingertips (\"grip\")")
      .def_readonly("hand", &PickPlaceRobot::hand, "body carrying the fingers (\"link6\")")
      .def_readonly("fingers", &PickPlaceRobot::fingers,
                    "the two finger joints; each finger's body and geom share its name")
      .def_property_readonly(
          "mount", [](const PickPlaceRobot& r) { return to_array(r.mount.data(), 3); },
          "where the robot's base stands in the arena (3,) [m]")
      .def_readonly("own_table", &PickPlaceRobot::own_table,
                    "the model brings its table (body \"table\"); else the arena's")
      .def_readonly("table_height", &PickPlaceRobot::table_height,
                    "height of the table's top surface [m]")
      .def_readonly("min_radius", &PickPlaceRobot::min_radius,
                    "smallest horizontal distance of a trial's points from the base axis [m]")
      .def_readonly("max_radius", &PickPlaceRobot::max_radius,
                    "largest horizontal distance of a trial's points from the base axis [m]")
      .def_readonly("max_bearing", &PickPlaceRobot::max_bearing,
                    "largest bearing of a trial's points from +x [rad]");
  m.def("pick_place_robots", &pick_place_robots, "The robots of the pick and place, in order.");
  m.def("pick_place_robot", &pick_place_robot, py::arg("name"), py::return_value_policy::copy,
        "The robot called name (mjarm.Error listing the choices).");

  auto scene_options = py::class_<PickPlaceSceneOptions>(m, "PickPlaceSceneOptions",
                                                         "What the scene of one trial is made of.");
  fields_init<PickPlaceSceneOptions>(scene_options, "PickPlaceSceneOptions");
  scene_options.def_readwrite("robot", &PickPlaceSceneOptions::robot,
                              "the robot's name (see pick_place_robots())");
  enum_property<PickPlaceSceneOptions>(
      scene_options, "mode", &PickPlaceSceneOptions::mode,
      [](const std::string& s) { return simulation_mode_named(s); }, "servo or motor model");
  scene_options.def_readwrite("object", &PickPlaceSceneOptions::object,
                              "the object's size, mass, friction, position and yaw");
  array_property<PickPlaceSceneOptions>(scene_options, "target", &PickPlaceSceneOptions::target,
                                        "where the object should end, x, y (2,) [m]");
  list_property<PickPlaceSceneOptions>(scene_options, "finger_travel",
                                       &PickPlaceSceneOptions::finger_travel,
                                       "[lower, upper] per finger [m]; empty: the model's");
  scene_options
      .def_readwrite("finger_servo_gain", &PickPlaceSceneOptions::finger_servo_gain, "0: model's")
      .def_readwrite("noslip_iterations", &PickPlaceSceneOptions::noslip_iterations,
                     "solver option noslip_iterations (0: MuJoCo's default, none)")
      .def_readwrite("impratio", &PickPlaceSceneOptions::impratio,
                     "MuJoCo's frictional-to-normal impedance ratio (≥ 1)");
  py::class_<PickPlaceScene>(
      m, "PickPlaceScene", "A composed pick-and-place scene and the (prefixed) names a run needs.")
      .def_readonly("model", &PickPlaceScene::model, "Robot: the compiled scene")
      .def_readonly("tool", &PickPlaceScene::tool,
                    "tool site between the fingertips (\"arm6/grip\")")
      .def_readonly("hand", &PickPlaceScene::hand, "body carrying the fingers (\"arm6/link6\")")
      .def_readonly("fingers", &PickPlaceScene::fingers,
                    "the two finger joints (= bodies = geoms, \"arm6/finger_left\")")
      .def_readonly("arm_joints", &PickPlaceScene::arm_joints,
                    "the arm's hinge joints, base to flange")
      .def_readonly("table", &PickPlaceScene::table, "table body (\"arm6/table\", \"arena/table\")")
      .def_readonly("robot_root", &PickPlaceScene::robot_root,
                    "body whose subtree is the robot (\"arm6/base\", \"panda\")")
      .def_readonly("object", &PickPlaceScene::object, "the free body (geom \"object/geom\")")
      .def_readonly("target", &PickPlaceScene::target,
                    "world site at the target (object centre at rest)")
      .def_readonly("weld", &PickPlaceScene::weld, "weld hand → object (inactive at the start)")
      .def_readonly("cameras", &PickPlaceScene::cameras,
                    "the scene's cameras: \"front\", \"side\", \"top\"")
      .def_readonly("table_height", &PickPlaceScene::table_height,
                    "height of the table's top surface [m]");
  m.def(
      "build_pick_place_scene",
      [](const PickPlaceSceneOptions& o) {
        py::gil_scoped_release release;
        return build_pick_place_scene(o);
      },
      py::arg("options"), "Composes and compiles the scene of one trial (GIL released).");
}

}  // namespace

void bind_pick_place(py::module_& m) {
  bind_pick_place_options(m);
  bind_pick_place_results(m);
  bind_scene_of_a_trial(m);

  auto batch = py::class_<PickPlaceBatchOptions>(
      m, "PickPlaceBatchOptions",
      "A batch: trial k runs base with seed base.seed + k, on threads workers (0: one per core).");
  fields_init<PickPlaceBatchOptions>(batch, "PickPlaceBatchOptions");
  batch.def_readwrite("base", &PickPlaceBatchOptions::base, "PickPlaceOptions of every trial")
      .def_readwrite("trials", &PickPlaceBatchOptions::trials, "number of trials (≥ 1)")
      .def_readwrite("threads", &PickPlaceBatchOptions::threads, ">= 0; 0: one per core")
      .def_readwrite("record", &PickPlaceBatchOptions::record,
                     "when set, trial k records into record/seed_<seed>");

  m.def("draw_pick_place_trial", &draw_pick_place_trial, py::arg("options"),
        "The trial options.seed draws (object, target), fixed values of the options in place.");
  m.def(
      "run_pick_place",
      [](const PickPlaceOptions& options) {
        return call_released([&] { return run_pick_place(options); });
      },
      py::arg("options"),
      "Runs one trial (GIL released): scene, reach check, the 14-state machine, the verdict. A "
      "trial that fails or diverges is a report with its reason; bad options or an unreachable "
      "object raise mjarm.Error; Ctrl-C raises KeyboardInterrupt.");
  m.def(
      "run_pick_place_trials",
      [](const PickPlaceBatchOptions& options, const py::object& on_progress) {
        PickPlaceBatchOptions o = options;
        // called from the workers, one at a time; a Python error is raised after the batch
        struct Progress {
          py::object f;
          std::exception_ptr error;
        };
        auto progress = std::make_shared<Progress>();
        if (!on_progress.is_none()) {
          progress->f = on_progress;
          o.on_progress = [progress](int done) {
            py::gil_scoped_acquire gil;
            if (progress->error) return;
            try {
              progress->f(done);
            } catch (...) {
              progress->error = std::current_exception();
            }
          };
        }
        PickPlaceBatch result = call_released([&] { return run_pick_place_trials(o); });
        if (progress->error) std::rethrow_exception(progress->error);
        return result;
      },
      py::arg("options"), py::arg("on_progress") = py::none(),
      "Runs options.trials trials in parallel (GIL released; the workers share nothing). "
      "on_progress(done) is called after each trial, one call at a time. Returns a "
      "PickPlaceBatch; Ctrl-C raises KeyboardInterrupt.");
  m.def("summarize", &summarize, py::arg("reports"),
        "The PickPlaceSummary of a list of PickPlaceReport.");
}

}  // namespace mjarm::python
