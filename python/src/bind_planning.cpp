// planning room: the waypoint planner and the joint spline it returns, Cartesian paths, the
// configuration checks they share.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/planning/cartesian_path.hpp"
#include "mjarm/planning/waypoint_planner.hpp"

namespace mjarm::python {

void bind_planning(py::module_& m) {
  py::class_<JointSpline>(m, "JointSpline", "A timed joint trajectory: quintic segments.")
      .def_property_readonly("empty", &JointSpline::empty, "True when the spline has no knots")
      .def_property_readonly("size", &JointSpline::size, "number of joints n (0 when empty)")
      .def_property_readonly("segments", &JointSpline::segments, "number of segments K")
      .def_property_readonly("duration", &JointSpline::duration, "total duration [s]")
      .def("knot_time", &JointSpline::knot_time, py::arg("k"))
      .def_property_readonly("knots", &JointSpline::knots,
                             "the knot positions (K + 1 arrays of shape (n,)) [rad or m]")
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
  plan_options.def(py::init<>())
      .def_readwrite("ik", &PlanOptions::ik, "the local IK from the previous waypoint");
  def_fields(plan_options);
  auto waypoint = py::class_<WaypointReport>(m, "WaypointReport", "What happened at one waypoint.");
  def_readonly_fields(waypoint);
  py::class_<PlanResult>(m, "PlanResult")
      .def_readonly("status", &PlanResult::status, "ok, or why planning failed")
      .def_readonly("failed_waypoint", &PlanResult::failed_waypoint,
                    "index of the waypoint that failed (−1: none, or the start)")
      .def_readonly("message", &PlanResult::message, "one line for people")
      .def_readonly("waypoints", &PlanResult::waypoints, "one report per waypoint reached or tried")
      .def_readonly("trajectory", &PlanResult::trajectory, "the timed trajectory (when ok)")
      .def_readonly("samples", &PlanResult::samples, "states checked along the trajectory")
      .def("ok", &PlanResult::ok);
  py::class_<WaypointPlanner>(m, "WaypointPlanner",
                              "Cartesian waypoints -> checked, timed joint trajectory (limits, "
                              "singularities, torque, contacts). plan() releases the GIL.")
      .def(py::init<const Chain&, const PlanOptions&>(), py::arg("chain"),
           py::arg("options") = PlanOptions{})
      .def_property_readonly("chain", &WaypointPlanner::chain, "the chain planned for")
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

  auto check_options = py::class_<CheckOptions>(m, "CheckOptions", "Thresholds of the checks.");
  check_options.def(py::init<>());
  def_fields(check_options);
  def_enum<CheckFailure>(m, "CheckFailure");
  py::class_<ConfigurationCheck>(m, "ConfigurationCheck", "What one state's checks measured.")
      .def_readonly("failure", &ConfigurationCheck::failure, "the first failed check (none)")
      .def_readonly("sigma_min", &ConfigurationCheck::sigma_min, "smallest singular value of J")
      .def_readonly("torque_ratio", &ConfigurationCheck::torque_ratio,
                    "largest |tau_i| / tau_max,i")
      .def_readonly("limit_joint", &ConfigurationCheck::limit_joint, "-1: none")
      .def_readonly("geom1", &ConfigurationCheck::geom1, "the deepest contact's moving geom")
      .def_readonly("geom2", &ConfigurationCheck::geom2, "the other geom of that contact")
      .def_readonly("distance", &ConfigurationCheck::distance, "its signed distance [m]")
      .def("ok", &ConfigurationCheck::ok);

  def_enum<CartesianPathStatus>(m, "CartesianPathStatus");
  auto cartesian_options = py::class_<CartesianPathOptions>(m, "CartesianPathOptions");
  cartesian_options.def(py::init<>())
      .def_readwrite("ik", &CartesianPathOptions::ik, "the local IK of each step (its tolerances)");
  def_fields(cartesian_options);
  py::class_<CartesianPathResult>(m, "CartesianPathResult", "What a Cartesian path reached.")
      .def_readonly("status", &CartesianPathResult::status, "complete, or why it stopped")
      .def_readonly("fraction", &CartesianPathResult::fraction, "share of the steps followed")
      .def_readonly("steps", &CartesianPathResult::steps, "steps of the whole path")
      .def_readonly("stopped_at_step", &CartesianPathResult::stopped_at_step, "-1 when complete")
      .def_readonly("stopped_at_waypoint", &CartesianPathResult::stopped_at_waypoint,
                    "the waypoint its segment leads to (-1 when complete)")
      .def_readonly("message", &CartesianPathResult::message, "one line for people")
      .def_readonly("knots", &CartesianPathResult::knots, "(n, knots): knot 0 is the start")
      .def_readonly("poses", &CartesianPathResult::poses, "E at each knot")
      .def_readonly("max_position_error", &CartesianPathResult::max_position_error,
                    "largest miss of a knot's position [m]")
      .def_readonly("max_orientation_error", &CartesianPathResult::max_orientation_error,
                    "largest miss of a knot's orientation [rad]")
      .def_readonly("max_joint_step", &CartesianPathResult::max_joint_step,
                    "largest joint motion between two knots [rad or m]")
      .def_readonly("check", &CartesianPathResult::check, "the failing state's checks")
      .def("complete", &CartesianPathResult::complete);
  py::class_<CartesianPathPlanner>(m, "CartesianPathPlanner",
                                   "Straight lines of E through waypoints, step by step (MoveIt's "
                                   "Cartesian paths). follow() releases the GIL.")
      .def(py::init<const Chain&, const CartesianPathOptions&>(), py::arg("chain"),
           py::arg("options") = CartesianPathOptions{})
      .def_property_readonly("options", &CartesianPathPlanner::options, "its steps and checks")
      .def(
          "set_fixed_qpos",
          [](CartesianPathPlanner& p, py::handle q) { p.set_fixed_qpos(to_vector(q, "qpos")); },
          py::arg("qpos"))
      .def(
          "follow",
          [](CartesianPathPlanner& p, py::handle q_start,
             const std::vector<py::object>& waypoints) {
            const Eigen::VectorXd q = to_vector(q_start, "q_start");
            std::vector<Pose> poses;
            for (const auto& w : waypoints) poses.push_back(to_pose(w, "waypoint"));
            py::gil_scoped_release release;
            return p.follow(q, poses);
          },
          py::arg("q_start"), py::arg("waypoints"), "waypoints: Poses (or 4x4 matrices)");
}

}  // namespace mjarm::python
