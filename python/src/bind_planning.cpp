// planning room: the waypoint planner and the joint spline it returns, Cartesian paths, the
// configuration checks they share.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/planning/cartesian_path.hpp"
#include "mjarm/planning/ompl_planner.hpp"
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

  def_enum<OmplPlannerType>(m, "OmplPlannerType");
  def_enum<OmplStatus>(m, "OmplStatus");
  auto ompl_options = py::class_<OmplOptions>(m, "OmplOptions");
  ompl_options.def(py::init<>())
      .def_property(
          "allowed_collisions",
          [](const OmplOptions& o) {
            std::vector<std::pair<std::string, std::string>> pairs;
            for (const AllowedCollision& a : o.allowed_collisions)
              pairs.emplace_back(a.first, a.second);
            return pairs;
          },
          [](OmplOptions& o, const std::vector<std::pair<std::string, std::string>>& pairs) {
            o.allowed_collisions.clear();
            for (const auto& [first, second] : pairs)
              o.allowed_collisions.push_back({first, second});
          },
          "pairs of geom or body names allowed to touch");
  def_fields(ompl_options);
  py::class_<OmplResult>(m, "OmplResult", "A plan: status, path, timings, the work it took.")
      .def_readonly("status", &OmplResult::status, "success, or why not")
      .def_readonly("message", &OmplResult::message, "one line for people")
      .def_readonly("path", &OmplResult::path, "joint-space knots, start to goal (on success)")
      .def_readonly("path_length", &OmplResult::path_length, "joint-space length [rad]")
      .def_readonly("planning_time", &OmplResult::planning_time, "wall-clock time of plan() [s]")
      .def_readonly("validity_checks", &OmplResult::validity_checks, "states judged")
      .def_readonly("goal_states", &OmplResult::goal_states, "collision-free goal configurations")
      .def_readonly("trajectory", &OmplResult::trajectory, "the blended spline (on success)")
      .def_readonly("time_optimal", &OmplResult::time_optimal,
                    "the time-optimal timing (a TimeOptimalPath), or None")
      .def_readonly("trajectory_samples", &OmplResult::trajectory_samples, "samples checked")
      .def("ok", &OmplResult::ok);
  py::class_<OmplPlanner>(m, "OmplPlanner",
                          "Collision-free joint-space planning on OMPL with MuJoCo's collision "
                          "detection. The plan_* methods release the GIL.")
      .def(py::init<const Chain&, const OmplOptions&>(), py::arg("chain"),
           py::arg("options") = OmplOptions{})
      .def_property_readonly("options", &OmplPlanner::options, "its planner, budget and checks")
      .def(
          "set_fixed_qpos",
          [](OmplPlanner& p, py::handle q) { p.set_fixed_qpos(to_vector(q, "qpos")); },
          py::arg("qpos"))
      .def(
          "plan",
          [](OmplPlanner& p, py::handle q_start, py::handle q_goal) {
            const Eigen::VectorXd start = to_vector(q_start, "q_start");
            const OmplGoal goal = JointGoal{to_vector(q_goal, "q_goal")};
            py::gil_scoped_release release;
            return p.plan(start, goal);
          },
          py::arg("q_start"), py::arg("q_goal"), "To a joint configuration.")
      .def(
          "plan_to_pose",
          [](OmplPlanner& p, py::handle q_start, py::handle X, double position_tolerance,
             double orientation_tolerance) {
            const Eigen::VectorXd start = to_vector(q_start, "q_start");
            const OmplGoal goal =
                PoseGoal{to_pose(X, "X_WT"), position_tolerance, orientation_tolerance};
            py::gil_scoped_release release;
            return p.plan(start, goal);
          },
          py::arg("q_start"), py::arg("X_WT"), py::arg("position_tolerance") = 1e-4,
          py::arg("orientation_tolerance") = 1e-3, "To a pose of the chain's frame (through IK).")
      .def(
          "plan_to_region",
          [](OmplPlanner& p, py::handle q_start, py::handle lower, py::handle upper, py::handle R,
             double orientation_tolerance) {
            const Eigen::VectorXd start = to_vector(q_start, "q_start");
            const OmplGoal goal =
                PoseRegionGoal{to_fixed<3>(lower, "lower"), to_fixed<3>(upper, "upper"),
                               to_fixed_matrix<3, 3>(R, "R_WT"), orientation_tolerance};
            py::gil_scoped_release release;
            return p.plan(start, goal);
          },
          py::arg("q_start"), py::arg("lower"), py::arg("upper"), py::arg("R_WT"),
          py::arg("orientation_tolerance") = 0.1,
          "To the frame's origin in a box [lower, upper], its orientation near R_WT.");
}

}  // namespace mjarm::python
