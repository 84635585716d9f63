// tasks room: the shelf pick (plan, run, report, metrics); pick and place (bind_pick_place.cpp)
// and docking (bind_docking.cpp).
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/tasks/shelf_pick/shelf_pick.hpp"
#include "spec_support.hpp"

namespace mjarm::python {

void bind_tasks(py::module_& m) {
  py::class_<PickCriteria> criteria(m, "PickCriteria", "When a pick counts as held.");
  criteria.def(py::init<>());
  def_fields(criteria);
  auto metrics = py::class_<PickMetrics>(m, "PickMetrics", "How a tip approached its target.");
  def_readonly_fields(metrics);
  def_enum<PickOutcome>(m, "PickOutcome");
  def_enum<PickPhase>(m, "PickPhase");
  py::class_<ShelfPickRequest>(m, "ShelfPickRequest")
      .def(py::init<>())
      .def_readwrite("robot", &ShelfPickRequest::robot,
                     "the robot's name (see shelf_pick_robots())")
      .def_readwrite("controller", &ShelfPickRequest::controller,
                     "the controller's name (see shelf_pick_controllers())")
      .def_property(
          "pick",
          [](const ShelfPickRequest& r) -> std::optional<Eigen::Vector3d> { return r.pick; },
          [](ShelfPickRequest& r, py::handle p) {
            if (p.is_none())
              r.pick.reset();
            else
              r.pick = to_fixed<3>(p, "pick");
          },
          "pick point (3,) [m], or None: drawn from the seed")
      .def_readwrite("seed", &ShelfPickRequest::seed, "seed of the drawn pick point")
      .def_readwrite("criteria", &ShelfPickRequest::criteria,
                     "when the pick counts as held (1 mm, 200 ms by default)");
  py::class_<ShelfPickOptions>(m, "ShelfPickOptions")
      .def(py::init<>())
      .def_readwrite("request", &ShelfPickOptions::request,
                     "robot, controller, pick point, seed, criteria")
      .def_readwrite("record", &ShelfPickOptions::record, "recording directory ('' = none)")
      .def_readwrite(
          "control_period", &ShelfPickOptions::control_period,
          "control period (0: one physics step; else a whole multiple of the timestep) [s]")
      .def_readwrite("max_acceleration", &ShelfPickOptions::max_acceleration,
                     "divergence bound on |q̈| [rad/s²]")
      .def_readwrite(
          "settle_time", &ShelfPickOptions::settle_time,
          "time allowed after the approach for entering the tolerance and holding (> 0) [s]")
      .def_readwrite("gain_scale", &ShelfPickOptions::gain_scale,
                     "the tuned gains scaled: stiffness x s, damping x sqrt(s)")
      .def_readwrite("state_decimation", &ShelfPickOptions::state_decimation,
                     "one state row every N physics steps when recording")
      .def_property(
          "video", [](const ShelfPickOptions& o) { return o.video.path; },
          [](ShelfPickOptions& o, const std::filesystem::path& p) { o.video.path = p; },
          "MP4 of the run ('' = none)")
      .def_property(
          "video_camera", [](const ShelfPickOptions& o) { return o.video.camera; },
          [](ShelfPickOptions& o, const std::string& c) { o.video.camera = c; },
          "camera of the video ('' = the default)");
  py::class_<ShelfPickReport>(m, "ShelfPickReport")
      .def_property_readonly(
          "robot", [](const ShelfPickReport& r) { return r.plan.robot->name; }, "the robot's name")
      .def_property_readonly(
          "controller", [](const ShelfPickReport& r) { return r.plan.controller; },
          "the controller that ran")
      .def_property_readonly(
          "pick", [](const ShelfPickReport& r) { return Eigen::Vector3d(r.plan.pick); },
          "the pick point in W (3,) [m]")
      .def_property_readonly(
          "approach_time", [](const ShelfPickReport& r) { return r.plan.goal.approach_time; },
          "duration of the planned approach [s]")
      .def_property_readonly(
          "q_start", [](const ShelfPickReport& r) { return r.plan.goal.q_start; },
          "joint positions at the start (n,) [rad]")
      .def_property_readonly(
          "q_target", [](const ShelfPickReport& r) { return r.plan.goal.q_target; },
          "joint positions at the pick point (n,) [rad]")
      .def_readonly("run", &ShelfPickReport::run,
                    "the simulation's account (status, end time, message)")
      .def_readonly("metrics", &ShelfPickReport::metrics,
                    "time to tolerance, overshoot, steady state, hold")
      .def_readonly("outcome", &ShelfPickReport::outcome, "held, or why not")
      .def_readonly("final_phase", &ShelfPickReport::final_phase, "the phase the run ended in")
      .def_readonly("time_limit", &ShelfPickReport::time_limit, "simulated time allowed [s]")
      .def_readonly("control_period", &ShelfPickReport::control_period,
                    "control period of the run [s]")
      .def_readonly("saturated_ticks", &ShelfPickReport::saturated_ticks,
                    "the most control ticks any one motor was clipped to its torque limit")
      .def_readonly("recording", &ShelfPickReport::recording,
                    "the recording directory (empty when not recorded)")
      .def_readonly("recording_error", &ShelfPickReport::recording_error,
                    "why the recording could not be completed (empty when it was)")
      .def_readonly("video", &ShelfPickReport::video, "the MP4 written (empty when no video)")
      .def_readonly("video_frames", &ShelfPickReport::video_frames,
                    "frames in the video: ⌊(end − start)·fps⌋ + 1")
      .def_readonly("video_written", &ShelfPickReport::video_written,
                    "a complete, playable MP4 of the run is at video")
      .def("ok", &ShelfPickReport::ok);
  m.def("shelf_pick_robots", [] {
    std::vector<std::string> names;
    for (const auto& r : shelf_pick_robots()) names.push_back(r.name);
    return names;
  });
  m.def("shelf_pick_controllers", &shelf_pick_controllers);
  m.def(
      "run_shelf_pick",
      [](const ShelfPickOptions& options) {
        py::gil_scoped_release release;
        return run_shelf_pick(options);
      },
      py::arg("options"),
      "Plans, simulates and measures one shelf pick (GIL released); see docs/tasks.md.");
  bind_pick_place(m);
  bind_docking(m);
}

}  // namespace mjarm::python
