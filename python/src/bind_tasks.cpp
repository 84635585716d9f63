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
      .def_readwrite("robot", &ShelfPickRequest::robot)
      .def_readwrite("controller", &ShelfPickRequest::controller)
      .def_property(
          "pick",
          [](const ShelfPickRequest& r) -> py::object {
            return r.pick ? py::cast(Eigen::Vector3d(*r.pick)) : py::none();
          },
          [](ShelfPickRequest& r, py::handle p) {
            if (p.is_none())
              r.pick.reset();
            else
              r.pick = to_fixed<3>(p, "pick");
          },
          "pick point (3,) [m], or None: drawn from the seed")
      .def_readwrite("seed", &ShelfPickRequest::seed)
      .def_readwrite("criteria", &ShelfPickRequest::criteria);
  py::class_<ShelfPickOptions>(m, "ShelfPickOptions")
      .def(py::init<>())
      .def_readwrite("request", &ShelfPickOptions::request)
      .def_readwrite("record", &ShelfPickOptions::record, "recording directory ('' = none)")
      .def_readwrite("control_period", &ShelfPickOptions::control_period)
      .def_readwrite("max_acceleration", &ShelfPickOptions::max_acceleration)
      .def_readwrite("settle_time", &ShelfPickOptions::settle_time)
      .def_readwrite("gain_scale", &ShelfPickOptions::gain_scale,
                     "the tuned gains scaled: stiffness x s, damping x sqrt(s)")
      .def_readwrite("state_decimation", &ShelfPickOptions::state_decimation)
      .def_property(
          "video", [](const ShelfPickOptions& o) { return o.video.path; },
          [](ShelfPickOptions& o, const std::filesystem::path& p) { o.video.path = p; },
          "MP4 of the run ('' = none)")
      .def_property(
          "video_camera", [](const ShelfPickOptions& o) { return o.video.camera; },
          [](ShelfPickOptions& o, const std::string& c) { o.video.camera = c; });
  py::class_<ShelfPickReport>(m, "ShelfPickReport")
      .def_property_readonly("robot", [](const ShelfPickReport& r) { return r.plan.robot->name; })
      .def_property_readonly("controller",
                             [](const ShelfPickReport& r) { return r.plan.controller; })
      .def_property_readonly("pick",
                             [](const ShelfPickReport& r) { return Eigen::Vector3d(r.plan.pick); })
      .def_property_readonly("approach_time",
                             [](const ShelfPickReport& r) { return r.plan.goal.approach_time; })
      .def_property_readonly("q_start",
                             [](const ShelfPickReport& r) { return r.plan.goal.q_start; })
      .def_property_readonly("q_target",
                             [](const ShelfPickReport& r) { return r.plan.goal.q_target; })
      .def_readonly("run", &ShelfPickReport::run)
      .def_readonly("metrics", &ShelfPickReport::metrics)
      .def_readonly("outcome", &ShelfPickReport::outcome)
      .def_readonly("final_phase", &ShelfPickReport::final_phase)
      .def_readonly("time_limit", &ShelfPickReport::time_limit)
      .def_readonly("control_period", &ShelfPickReport::control_period)
      .def_readonly("saturated_ticks", &ShelfPickReport::saturated_ticks)
      .def_readonly("recording", &ShelfPickReport::recording)
      .def_readonly("recording_error", &ShelfPickReport::recording_error)
      .def_readonly("video", &ShelfPickReport::video)
      .def_readonly("video_frames", &ShelfPickReport::video_frames)
      .def_readonly("video_written", &ShelfPickReport::video_written)
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
