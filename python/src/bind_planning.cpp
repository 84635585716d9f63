// planning room: the waypoint planner and the joint spline it returns.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/planning/waypoint_planner.hpp"

namespace mjarm::python {

void bind_planning(py::module_& m) {
  py::class_<JointSpline>(m, "JointSpline", "A timed joint trajectory: quintic segments.")
      .def_property_readonly("empty", &JointSpline::empty)
      .def_property_readonly("size", &JointSpline::size)
      .def_property_readonly("segments", &JointSpline::segments)
      .def_property_readonly("duration", &JointSpline::duration, "[s]")
      .def("knot_time", &JointSpline::knot_time, py::arg("k"))
      .def_property_readonly("knots", &JointSpline::knots)
      .def(
          "at",
          [](const JointSpline& s, double t) {
            if (s.empty()) throw Error("JointSpline.at: the spline is empty (the plan failed)");
            Eigen::VectorXd q(s.size()), qd(s.size()), qdd(s.size());
            s.at(t, q, qd, qdd);
            return py::make_tuple(q, qd, qdd);
          },
          py::arg("t"), "(q, qd, qdd), each (n,)");

  def_enum<PlanStatus>(m, "PlanStatus");
  py::class_<PlanOptions> plan_options(m, "PlanOptions");
  plan_options.def(py::init<>()).def_readwrite("ik", &PlanOptions::ik);
  def_fields(plan_options);
  py::class_<WaypointReport>(m, "WaypointReport")
      .def_readonly("index", &WaypointReport::index)
      .def_readonly("X_WT", &WaypointReport::X_WT)
      .def_readonly("q", &WaypointReport::q)
      .def_readonly("ik", &WaypointReport::ik)
      .def_readonly("position_error", &WaypointReport::position_error)
      .def_readonly("orientation_error", &WaypointReport::orientation_error)
      .def_readonly("branch", &WaypointReport::branch)
      .def_readonly("detour", &WaypointReport::detour)
      .def_readonly("min_sigma", &WaypointReport::min_sigma)
      .def_readonly("max_torque_ratio", &WaypointReport::max_torque_ratio)
      .def_readonly("time", &WaypointReport::time)
      .def_readonly("message", &WaypointReport::message);
  py::class_<PlanResult>(m, "PlanResult")
      .def_readonly("status", &PlanResult::status)
      .def_readonly("failed_waypoint", &PlanResult::failed_waypoint)
      .def_readonly("message", &PlanResult::message)
      .def_readonly("waypoints", &PlanResult::waypoints)
      .def_readonly("trajectory", &PlanResult::trajectory)
      .def_readonly("samples", &PlanResult::samples)
      .def("ok", &PlanResult::ok);
  py::class_<WaypointPlanner>(m, "WaypointPlanner",
                              "Cartesian waypoints -> checked, timed joint trajectory (limits, "
                              "singularities, torque, contacts). plan() releases the GIL.")
      .def(py::init<const Chain&, const PlanOptions&>(), py::arg("chain"),
           py::arg("options") = PlanOptions{})
      .def_property_readonly("chain", &WaypointPlanner::chain)
      .def(
          "set_fixed_qpos",
          [](WaypointPlanner& p, py::handle q) {
            p.set_fixed_qpos(to_vector(q, "qpos", p.chain().robot().nq()));
          },
          py::arg("qpos"))
      .def(
          "plan",
          [](WaypointPlanner& p, py::handle q_start, const std::vector<py::object>& waypoints) {
            const Eigen::VectorXd q = to_vector(q_start, "q_start", p.chain().size());
            std::vector<Pose> poses;
            for (const auto& w : waypoints) poses.push_back(to_pose(w, "waypoint"));
            py::gil_scoped_release release;
            return p.plan(q, poses);
          },
          py::arg("q_start"), py::arg("waypoints"), "waypoints: Poses (or 4x4 matrices)");
}

}  // namespace mjarm::python
