// trajectory room: trapezoid, smoothstep family, quintics and their shortest duration, SE(3)
// interpolation, the jerk-limited online generator.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/path/joint_path.hpp"
#include "mjarm/trajectory/path/time_optimal_path.hpp"
#include "mjarm/trajectory/quintic.hpp"
#include "mjarm/trajectory/quintic_duration.hpp"
#include "mjarm/trajectory/se3_interpolation.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/trajectory/trapezoid.hpp"

namespace mjarm::python {
namespace {

/// (k, 3) array of positions, velocities, accelerations -> states.
std::vector<KinematicState> states(py::handle a, const char* name, int dofs) {
  const Eigen::MatrixXd M = to_matrix(a, name, dofs, 3);
  std::vector<KinematicState> s(static_cast<std::size_t>(M.rows()));
  for (Eigen::Index i = 0; i < M.rows(); ++i) s[i] = {M(i, 0), M(i, 1), M(i, 2)};
  return s;
}

QuinticTrajectory::State joint_state(py::handle q, py::handle qd, py::handle qdd, Eigen::Index n,
                                     const char* which) {
  const std::string w(which);
  QuinticTrajectory::State s;
  s.q = to_vector(q, (w + ".q").c_str(), n);
  const Eigen::Index size = s.q.size();
  s.qd = qd.is_none() ? Eigen::VectorXd::Zero(size) : to_vector(qd, (w + ".qd").c_str(), size);
  s.qdd = qdd.is_none() ? Eigen::VectorXd::Zero(size) : to_vector(qdd, (w + ".qdd").c_str(), size);
  return s;
}

}  // namespace

void bind_trajectory(py::module_& m) {
  py::class_<TrapezoidProfile::Sample>(m, "TrapezoidSample")
      .def_readonly("position", &TrapezoidProfile::Sample::position, "distance covered, 0 … d [u]")
      .def_readonly("velocity", &TrapezoidProfile::Sample::velocity, "speed, ≥ 0 [u/s]")
      .def_readonly("acceleration", &TrapezoidProfile::Sample::acceleration, "+a, 0 or −a [u/s²]")
      .def_readonly("fraction", &TrapezoidProfile::Sample::fraction, "position/d in [0, 1]");
  py::class_<TrapezoidProfile>(m, "TrapezoidProfile", "Rest-to-rest trapezoidal velocity profile.")
      .def(py::init<double, double, double>(), py::arg("distance"),
           py::arg("max_velocity") = TrapezoidProfile::kDefaultMaxVelocity,
           py::arg("max_acceleration") = TrapezoidProfile::kDefaultMaxAcceleration)
      .def_property_readonly("distance", &TrapezoidProfile::distance, "the distance d [u]")
      .def_property_readonly("duration", &TrapezoidProfile::duration, "the duration T [s]")
      .def_property_readonly(
          "peak_velocity", &TrapezoidProfile::peak_velocity,
          "the highest speed reached (v_max for a trapezoid, less for a triangle) [u/s]")
      .def_property_readonly("triangular", &TrapezoidProfile::triangular,
                             "True when v_max is never reached: the profile is a triangle")
      .def("at", py::overload_cast<double>(&TrapezoidProfile::at, py::const_), py::arg("t"))
      .def("fraction", &TrapezoidProfile::fraction, py::arg("t"));
  m.def("trap_profile", &trap_profile, py::arg("distance"),
        py::arg("max_velocity") = TrapezoidProfile::kDefaultMaxVelocity,
        py::arg("max_acceleration") = TrapezoidProfile::kDefaultMaxAcceleration);
  m.def("trap_frac", &trap_frac, py::arg("profile"), py::arg("t"));
  py::class_<SyncedTrapezoid>(m, "SyncedTrapezoid", "Trapezoids on n axes finishing together.")
      .def(py::init([](py::handle a, py::handle b, double v, double acc) {
             const Eigen::VectorXd start = to_vector(a, "start");
             return SyncedTrapezoid(start, to_vector(b, "goal", start.size()), v, acc);
           }),
           py::arg("start"), py::arg("goal"), py::arg("max_velocity"), py::arg("max_acceleration"))
      .def_property_readonly("duration", &SyncedTrapezoid::duration,
                             "the common duration T (0 when start equals goal) [s]")
      .def_property_readonly("limiting_axis", &SyncedTrapezoid::limiting_axis,
                             "the axis that needs the longest time (it moves at its own limits)")
      .def(
          "at",
          [](const SyncedTrapezoid& s, double t) {
            const auto n = static_cast<Eigen::Index>(s.size());
            Eigen::VectorXd p(n), v(n), a(n);
            s.at(t, p, v, a);
            return py::make_tuple(p, v, a);
          },
          py::arg("t"), "(position, velocity, acceleration), each (n,)");

  py::class_<RampSample>(m, "RampSample")
      .def_readonly("s", &RampSample::s, "value in [0, 1]")
      .def_readonly("ds", &RampSample::ds, "first derivative ds/dx")
      .def_readonly("dds", &RampSample::dds, "second derivative d²s/dx²")
      .def_readonly("ddds", &RampSample::ddds, "third derivative d³s/dx³");
  m.def("smoothstep", &smoothstep, py::arg("x"), "x^2 (3 - 2x) and its derivatives");
  m.def("smootherstep", &smootherstep, py::arg("x"), "6x^5 - 15x^4 + 10x^3 and its derivatives");

  py::class_<Quintic::Sample>(m, "QuinticSample")
      .def_readonly("p", &Quintic::Sample::p, "position [u]")
      .def_readonly("v", &Quintic::Sample::v, "velocity [u/s]")
      .def_readonly("a", &Quintic::Sample::a, "acceleration [u/s²]")
      .def_readonly("j", &Quintic::Sample::j, "jerk [u/s³]");
  py::class_<Quintic>(m, "Quintic", "A quintic between two (p, v, a) states over a duration.")
      .def(py::init([](py::handle start, py::handle end, double T) {
             const Eigen::Vector3d a = to_fixed<3>(start, "start"), b = to_fixed<3>(end, "end");
             return Quintic({a[0], a[1], a[2]}, {b[0], b[1], b[2]}, T);
           }),
           py::arg("start"), py::arg("end"), py::arg("duration"), "start, end: (p, v, a)")
      .def_property_readonly("duration", &Quintic::duration, "the duration T [s]")
      .def_property_readonly("coefficients", &Quintic::coefficients,
                             "the coefficients c₀ … c₅ in powers of t (6,)")
      .def("at", py::overload_cast<double>(&Quintic::at, py::const_), py::arg("t"));
  py::class_<QuinticTrajectory>(m, "QuinticTrajectory", "n joints, one quintic each.")
      .def(py::init([](py::handle q0, py::handle q1, double T, py::handle qd0, py::handle qdd0,
                       py::handle qd1, py::handle qdd1) {
             const auto start = joint_state(q0, qd0, qdd0, -1, "start");
             const auto end = joint_state(q1, qd1, qdd1, start.q.size(), "end");
             return QuinticTrajectory(start, end, T);
           }),
           py::arg("q_start"), py::arg("q_end"), py::arg("duration"),
           py::arg("qd_start") = py::none(), py::arg("qdd_start") = py::none(),
           py::arg("qd_end") = py::none(), py::arg("qdd_end") = py::none())
      .def_property_readonly("duration", &QuinticTrajectory::duration, "the duration T [s]")
      .def_property_readonly("size", &QuinticTrajectory::size, "the number of joints n")
      .def(
          "at",
          [](const QuinticTrajectory& tr, double t) {
            Eigen::VectorXd q(tr.size()), qd(tr.size()), qdd(tr.size());
            tr.at(t, q, qd, qdd);
            return py::make_tuple(q, qd, qdd);
          },
          py::arg("t"), "(q, qd, qdd), each (n,)");
  py::enum_<QuinticDurationStatus>(m, "QuinticDurationStatus")
      .value("ok", QuinticDurationStatus::ok)
      .value("start_beyond_limits", QuinticDurationStatus::start_beyond_limits)
      .value("end_beyond_limits", QuinticDurationStatus::end_beyond_limits)
      .value("infeasible", QuinticDurationStatus::infeasible);
  py::class_<QuinticDuration>(m, "QuinticDuration")
      .def_readonly("status", &QuinticDuration::status, "ok, or why no duration was found")
      .def_readonly("duration", &QuinticDuration::duration, "the shortest feasible T (when ok) [s]")
      .def_readonly("limiting_joint", &QuinticDuration::limiting_joint,
                    "the joint whose limit is met at T (−1: none, T = floor)")
      .def_readonly("velocity_limited", &QuinticDuration::velocity_limited,
                    "True: its velocity limit is met; False: its acceleration limit");
  m.def(
      "shortest_quintic_duration",
      [](py::handle q0, py::handle q1, py::handle vmax, py::handle amax, double min_duration) {
        const auto start = joint_state(q0, py::none(), py::none(), -1, "start");
        const auto end = joint_state(q1, py::none(), py::none(), start.q.size(), "end");
        return shortest_quintic_duration(
            start, end, to_vector(vmax, "max_velocity", start.q.size()),
            to_vector(amax, "max_acceleration", start.q.size()), min_duration);
      },
      py::arg("q_start"), py::arg("q_end"), py::arg("max_velocity"), py::arg("max_acceleration"),
      py::arg("min_duration") = 0.0, "rest to rest: the exact shortest duration within the limits");

  py::class_<Se3Interpolation::Sample>(m, "Se3Sample")
      .def_readonly("X_WE", &Se3Interpolation::Sample::X_WE, "pose of E in W")
      .def_property_readonly(
          "V_WE", [](const Se3Interpolation::Sample& s) { return Vector6d(s.V_WE); },
          "spatial velocity, world axes, linear first (6,) [m/s, rad/s]")
      .def_property_readonly(
          "A_WE", [](const Se3Interpolation::Sample& s) { return Vector6d(s.A_WE); },
          "spatial acceleration, world axes, linear first (6,) [m/s², rad/s²]");
  py::class_<Se3Interpolation>(m, "Se3Interpolation",
                               "Pose interpolation that may start in motion (world axes).")
      .def(py::init([](py::handle X0, py::handle X1, double T, py::handle V0, py::handle A0) {
             const Vector6d v =
                 V0.is_none() ? Vector6d::Zero() : Vector6d(to_fixed<6>(V0, "V_start"));
             const Vector6d a =
                 A0.is_none() ? Vector6d::Zero() : Vector6d(to_fixed<6>(A0, "A_start"));
             return Se3Interpolation(to_pose(X0, "X_start"), v, a, to_pose(X1, "X_goal"), T);
           }),
           py::arg("X_start"), py::arg("X_goal"), py::arg("duration"),
           py::arg("V_start") = py::none(), py::arg("A_start") = py::none())
      .def_property_readonly("duration", &Se3Interpolation::duration, "the duration T [s]")
      .def("at", &Se3Interpolation::at, py::arg("t"));

  def_enum<OtgStatus>(m, "OtgStatus");
  py::class_<OtgResult>(m, "OtgResult")
      .def_readonly("status", &OtgResult::status, "outcome of the calculation")
      .def_readonly("duration", &OtgResult::duration, "synchronized duration, brake included [s]")
      .def_readonly("limiting_dof", &OtgResult::limiting_dof, "the DoF that sets the duration")
      .def_readonly("failed_dof", &OtgResult::failed_dof,
                    "the DoF that failed (error statuses only)")
      .def_readonly("end_error", &OtgResult::end_error,
                    "largest end miss over the DoFs, relative to max(1, |start|, |target|)")
      .def_readonly("limit_excess", &OtgResult::limit_excess,
                    "largest relative limit excess after the brakes (<= 0 within the limits)")
      .def_readonly("sync_error", &OtgResult::sync_error,
                    "largest |profile duration - duration| over the DoFs [s]");
  py::class_<JerkLimitedGenerator>(
      m, "JerkLimitedGenerator",
      "Synchronized jerk-limited trajectories for n DoF. States are (n, 3) arrays of (p, v, a).")
      .def(py::init([](py::handle limits) {
             const Eigen::MatrixXd L = to_matrix(limits, "limits", -1, 3);
             std::vector<JerkLimits> l(static_cast<std::size_t>(L.rows()));
             for (Eigen::Index i = 0; i < L.rows(); ++i) l[i] = {L(i, 0), L(i, 1), L(i, 2)};
             return JerkLimitedGenerator(l);
           }),
           py::arg("limits"), "limits (n, 3): velocity, acceleration, jerk per DoF")
      .def_property_readonly("dofs", &JerkLimitedGenerator::dofs, "number of degrees of freedom")
      .def(
          "calculate",
          [](JerkLimitedGenerator& g, py::handle current, py::handle target) {
            return g.calculate(states(current, "current", g.dofs()),
                               states(target, "target", g.dofs()));
          },
          py::arg("current"), py::arg("target"))
      .def(
          "calculate_velocity",
          [](JerkLimitedGenerator& g, py::handle current, py::handle target) {
            return g.calculate_velocity(states(current, "current", g.dofs()),
                                        states(target, "target", g.dofs()));
          },
          py::arg("current"), py::arg("target"))
      .def_property_readonly("duration", &JerkLimitedGenerator::duration,
                             "synchronized duration of the last calculation [s]")
      .def_property_readonly("result", &JerkLimitedGenerator::result,
                             "the result of the last calculation")
      .def(
          "at",
          [](const JerkLimitedGenerator& g, double t) {
            std::vector<JerkSample> s(static_cast<std::size_t>(g.dofs()));
            g.at(t, s);
            Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> out(g.dofs(), 4);
            for (int i = 0; i < g.dofs(); ++i) out.row(i) << s[i].p, s[i].v, s[i].a, s[i].j;
            return out;
          },
          py::arg("t"), "(n, 4): position, velocity, acceleration, jerk at t [s]");

  py::class_<JointPath>(m, "JointPath",
                        "A C2 cubic spline through joint waypoints, by chord length (untimed).")
      .def(py::init([](const std::vector<py::object>& waypoints) {
             std::vector<Eigen::VectorXd> q;
             for (const auto& w : waypoints) q.push_back(to_vector(w, "waypoint"));
             return JointPath(q);
           }),
           py::arg("waypoints"), "waypoints: arrays of n joint values (at least 2, distinct)")
      .def_property_readonly("dofs", &JointPath::dofs, "joints n")
      .def_property_readonly("length", &JointPath::length, "chord length L of the path [rad or m]")
      .def(
          "evaluate",
          [](const JointPath& path, double s) {
            Eigen::VectorXd q(path.dofs()), dq(path.dofs()), ddq(path.dofs());
            path.evaluate(s, q, dq, ddq);
            return py::make_tuple(q, dq, ddq);
          },
          py::arg("s"), "(q, dq/ds, d2q/ds2) at the path parameter s");
  auto topp_options = py::class_<ToppOptions>(m, "ToppOptions");
  topp_options.def(py::init<>());
  def_fields(topp_options);
  def_enum<ToppStatus>(m, "ToppStatus");
  py::class_<TimeOptimalPath>(m, "TimeOptimalPath",
                              "A JointPath timed as fast as the velocity and acceleration limits "
                              "allow (TOPP-RA), rest to rest.")
      .def(py::init(
               [](const JointPath& path, py::handle v, py::handle a, const ToppOptions& options) {
                 return TimeOptimalPath(path, to_vector(v, "max_velocity", path.dofs()),
                                        to_vector(a, "max_acceleration", path.dofs()), options);
               }),
           py::arg("path"), py::arg("max_velocity"), py::arg("max_acceleration"),
           py::arg("options") = ToppOptions{})
      .def_property_readonly("status", &TimeOptimalPath::status, "solved, or infeasible")
      .def("solved", &TimeOptimalPath::solved)
      .def_property_readonly("duration", &TimeOptimalPath::duration,
                             "duration of the motion [s] (0 unless solved)")
      .def_property_readonly("path", &TimeOptimalPath::path, "the path timed")
      .def_property_readonly(
          "grid_times", [](const TimeOptimalPath& p) { return Eigen::VectorXd(p.grid_times()); },
          "the time of each grid point (N + 1,) [s]")
      .def(
          "at",
          [](const TimeOptimalPath& p, double t) {
            TrajectorySample s(p.dofs());
            p.at(t, s);
            return py::make_tuple(s.position, s.velocity, s.acceleration);
          },
          py::arg("t"), "(q, qd, qdd) at t [s], clamped to [0, T]");
}

}  // namespace mjarm::python
