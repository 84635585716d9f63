// dynamics room: ChainDynamics, TaskSpaceDynamics, F/T sensor, momentum observer, friction.
#include "bindings.hpp"
#include "declared_fields.hpp"
#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/force_torque_sensor.hpp"
#include "mjarm/dynamics/friction_feed_forward.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/dynamics/task_space.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm::python {
namespace {

const mjData& sensor_data(const ForceTorqueSensor& s, const DataHandle& d, const char* call) {
  return data_of(s.model(), "the sensor's model '" + model_name(s.model()) + "'", d, call);
}

}  // namespace

void bind_dynamics(py::module_& m) {
  py::class_<ChainDynamics>(m, "ChainDynamics",
                            "Joint-space dynamics of a chain read from an up-to-date Data (after "
                            "forward): M, bias h, gravity g, J, J̇q̇, inverse dynamics.")
      .def(py::init<const Chain&>(), py::arg("chain"))
      .def_property_readonly("chain", &ChainDynamics::chain,
                             "the chain the dynamics are restricted to")
      .def_property_readonly("size", &ChainDynamics::size, "number of chain dofs n")
      .def(
          "update",
          [](ChainDynamics& dyn, const DataHandle& d) {
            dyn.update(
                data_of(dyn.chain().robot(), d, "ChainDynamics.update", "the chain's model"));
          },
          py::arg("data"), "Reads everything from data (never writes it).")
      .def_property_readonly(
          "q", [](const ChainDynamics& d) { return Eigen::VectorXd(d.q()); },
          "chain joint positions at the last update() (n,) [rad or m]")
      .def_property_readonly(
          "qd", [](const ChainDynamics& d) { return Eigen::VectorXd(d.qd()); },
          "chain joint velocities at the last update() (n,) [rad/s or m/s]")
      .def_property_readonly(
          "mass_matrix", [](const ChainDynamics& d) { return Eigen::MatrixXd(d.mass_matrix()); },
          "joint-space inertia M, armature included (n, n) [kg·m² or kg]")
      .def_property_readonly(
          "bias", [](const ChainDynamics& d) { return Eigen::VectorXd(d.bias()); },
          "bias forces h = C(q, q̇)·q̇ + g(q) on the chain's dofs (n,) [N·m or N]")
      .def_property_readonly(
          "gravity", [](const ChainDynamics& d) { return Eigen::VectorXd(d.gravity()); },
          "gravity torques g(q) that hold the arm still (n,) [N·m or N]")
      .def_property_readonly(
          "pose", [](const ChainDynamics& d) { return d.pose(); },
          "pose X_WE of the chain's frame at the last update()")
      .def_property_readonly(
          "jacobian", [](const ChainDynamics& d) { return Matrix6Xd(d.jacobian()); },
          "world-aligned J (6, n)")
      .def_property_readonly(
          "velocity", [](const ChainDynamics& d) { return Vector6d(d.velocity()); },
          "spatial velocity V_WE = [v; ω] of E, world axes (6,) [m/s, rad/s]")
      .def_property_readonly(
          "bias_acceleration",
          [](const ChainDynamics& d) { return Vector6d(d.bias_acceleration()); },
          "bias acceleration J̇·q̇ of E, world-aligned, linear first (6,) [m/s², rad/s²]")
      .def(
          "inverse_dynamics",
          [](ChainDynamics& dyn, const DataHandle& d, py::handle qdd) {
            const mjData& data = data_of(dyn.chain().robot(), d,
                                         "ChainDynamics.inverse_dynamics", "the chain's model");
            Eigen::VectorXd tau(dyn.size());
            dyn.inverse_dynamics(data, to_vector(qdd, "qdd", dyn.size()), tau);
            return tau;
          },
          py::arg("data"), py::arg("qdd"), "tau = M qdd + h (n,)");

  def_enum<TaskSpaceStatus>(m, "TaskSpaceStatus");
  auto task_space_options = py::class_<TaskSpaceOptions>(m, "TaskSpaceOptions");
  task_space_options.def(py::init<>());
  def_fields(task_space_options);
  py::class_<TaskSpaceDynamics>(m, "TaskSpaceDynamics",
                                "Lambda = (J M^-1 J^T)^-1, Jbar and the null-space projector, "
                                "bounded near singularities.")
      .def(py::init<int, int, TaskSpaceOptions>(), py::arg("dofs"), py::arg("task_rows") = 6,
           py::arg("options") = TaskSpaceOptions{})
      .def(
          "update",
          [](TaskSpaceDynamics& t, py::handle M, py::handle J) {
            return t.update(to_matrix(M, "M", t.dofs(), t.dofs()),
                            to_matrix(J, "J", t.task_rows(), t.dofs()));
          },
          py::arg("M"), py::arg("J"))
      .def(
          "update_from",
          [](TaskSpaceDynamics& t, const ChainDynamics& d) {
            if (d.size() != t.dofs()) throw Error("TaskSpaceDynamics.update_from: dofs differ");
            return t.update(d);
          },
          py::arg("dynamics"))
      .def_property_readonly("status", &TaskSpaceDynamics::status, "status of the last update")
      .def_property_readonly(
          "lambda_", [](const TaskSpaceDynamics& t) { return Eigen::MatrixXd(t.lambda()); },
          "task-space inertia Λ (m, m) [kg for linear rows, kg·m² for angular rows]")
      .def_property_readonly(
          "lambda_inverse",
          [](const TaskSpaceDynamics& t) { return Eigen::MatrixXd(t.lambda_inverse()); },
          "Λ⁻¹ = J·M⁻¹·Jᵀ as computed, before flooring (m, m)")
      .def_property_readonly(
          "jbar", [](const TaskSpaceDynamics& t) { return Eigen::MatrixXd(t.jbar()); },
          "dynamically consistent inverse J̄ = M⁻¹·Jᵀ·Λ (n, m)")
      .def_property_readonly(
          "nullspace", [](const TaskSpaceDynamics& t) { return Eigen::MatrixXd(t.nullspace()); },
          "null-space projector N = I − J̄·J (n, n)")
      .def_property_readonly(
          "mass_inverse",
          [](const TaskSpaceDynamics& t) { return Eigen::MatrixXd(t.mass_inverse()); },
          "inverse joint-space inertia M⁻¹ (n, n)")
      .def_property_readonly(
          "eigenvalues",
          [](const TaskSpaceDynamics& t) { return Eigen::VectorXd(t.eigenvalues()); },
          "eigenvalues of J·M⁻¹·Jᵀ, ascending, before flooring (m,)")
      .def_property_readonly("min_singular_value", &TaskSpaceDynamics::min_singular_value,
                             "smallest singular value of J·M^(−1/2); → 0 at a singularity")
      .def_property_readonly("condition", &TaskSpaceDynamics::condition,
                             "condition number of J·M⁻¹·Jᵀ (+inf when singular)");

  def_enum<SensorTiming>(m, "SensorTiming");
  def_enum<WrenchStatus>(m, "WrenchStatus");
  py::class_<WrenchReading>(m, "WrenchReading")
      .def_property_readonly(
          "wrench", [](const WrenchReading& r) { return Vector6d(r.wrench); },
          "the wrench [f; τ], linear first, in the axes and about the point asked for (6,) [N, "
          "N·m]")
      .def_readonly("time", &WrenchReading::time,
                    "simulation time at which the value was measured [s]")
      .def_readonly("age", &WrenchReading::age,
                    "d.time − time: one physics timestep for after_step, 0 otherwise [s]")
      .def_readonly("status", &WrenchReading::status, "ok, or non_finite (wrench zeroed)")
      .def("ok", &WrenchReading::ok);
  py::class_<ForceTorqueSensor>(m, "ForceTorqueSensor", "F/T sensor pair on a site.")
      .def(py::init<const Robot&, std::string_view, SensorTiming>(), py::arg("robot"),
           py::arg("site"), py::arg("timing") = SensorTiming::after_step, py::keep_alive<1, 2>())
      .def_property_readonly("site", &ForceTorqueSensor::site, "the site's name")
      .def(
          "read_site",
          [](const ForceTorqueSensor& s, const DataHandle& d) {
            return s.read_site(sensor_data(s, d, "ForceTorqueSensor.read_site"));
          },
          py::arg("data"), "wrench in the site's frame")
      .def(
          "read_world",
          [](const ForceTorqueSensor& s, const DataHandle& d, py::handle p) {
            return s.read_world(sensor_data(s, d, "ForceTorqueSensor.read_world"),
                                to_fixed<3>(p, "p_WP"));
          },
          py::arg("data"), py::arg("p_WP"), "wrench in world axes about p_WP")
      .def(
          "read_body",
          [](const ForceTorqueSensor& s, const DataHandle& d, py::handle X) {
            return s.read_body(sensor_data(s, d, "ForceTorqueSensor.read_body"),
                               to_pose(X, "X_WE"));
          },
          py::arg("data"), py::arg("X_WE"));
  m.def(
      "shift_wrench",
      [](py::handle F, py::handle a, py::handle b) {
        return shift_wrench(to_fixed<6>(F, "F"), to_fixed<3>(a, "p_A"), to_fixed<3>(b, "p_B"));
      },
      py::arg("F"), py::arg("p_A"), py::arg("p_B"), "moves the torque's reference point");

  def_enum<FrictionMode>(m, "FrictionMode");
  def_enum<DampingCompensation>(m, "DampingCompensation");
  auto friction_options = py::class_<FrictionFeedForwardOptions>(m, "FrictionFeedForwardOptions");
  friction_options.def(py::init<>());
  def_fields(friction_options);
  py::class_<FrictionFeedForward>(m, "FrictionFeedForward", "Friction and damping feed-forward.")
      .def(py::init<const Chain&, FrictionFeedForwardOptions>(), py::arg("chain"),
           py::arg("options") = FrictionFeedForwardOptions{})
      .def_property_readonly(
          "friction", [](const FrictionFeedForward& f) { return Eigen::VectorXd(f.friction()); },
          "Coulomb friction per dof (n,) [N·m or N]")
      .def_property_readonly(
          "damping", [](const FrictionFeedForward& f) { return Eigen::VectorXd(f.damping()); },
          "viscous damping per dof (n,) [N·m·s/rad or N·s/m]")
      .def("active", &FrictionFeedForward::active)
      .def(
          "apply",
          [](const FrictionFeedForward& f, py::handle qd, py::handle tau) {
            Eigen::VectorXd t = to_vector(tau, "tau", f.size());
            f.apply(to_vector(qd, "qd", f.size()), t);
            return t;
          },
          py::arg("qd"), py::arg("tau"), "tau with the feed-forward added (n,)")
      .def(
          "model_force",
          [](const FrictionFeedForward& f, py::handle qd) {
            Eigen::VectorXd out(f.size());
            f.model_force(to_vector(qd, "qd", f.size()), out);
            return out;
          },
          py::arg("qd"));

  def_enum<ObserverStatus>(m, "ObserverStatus");
  def_enum<CoriolisMethod>(m, "CoriolisMethod");
  auto observer_options = py::class_<MomentumObserverOptions>(m, "MomentumObserverOptions");
  observer_options.def(py::init<>());
  def_fields(observer_options);
  py::class_<MomentumObserver>(m, "MomentumObserver", "Sensorless external wrench estimate.")
      .def(py::init<const Chain&, MomentumObserverOptions>(), py::arg("chain"),
           py::arg("options") = MomentumObserverOptions{})
      .def("reset", &MomentumObserver::reset)
      .def(
          "update",
          [](MomentumObserver& o, const DataHandle& d, const ChainDynamics& dyn, py::handle tau,
             double dt) {
            const mjData& data =
                data_of(o.chain().robot(), d, "MomentumObserver.update", "the chain's model");
            if (&dyn.chain().robot().model() != &o.chain().robot().model())
              throw Error("MomentumObserver.update: dynamics is of another chain's model");
            return o.update(data, dyn, to_vector(tau, "tau", o.size()), dt);
          },
          py::arg("data"), py::arg("dynamics"), py::arg("tau"), py::arg("dt"))
      .def_property_readonly(
          "residual", [](const MomentumObserver& o) { return Eigen::VectorXd(o.residual()); },
          "residual r: all disturbance torques (n,) [N·m or N]")
      .def_property_readonly(
          "momentum", [](const MomentumObserver& o) { return Eigen::VectorXd(o.momentum()); },
          "generalized momentum p = M·q̇ (n,) [kg·m²/s or kg·m/s]")
      .def_property_readonly(
          "wrench", [](const MomentumObserver& o) { return Vector6d(o.wrench()); },
          "wrench estimate from r, world axes about E's origin, [f; τ] (6,) [N, N·m]")
      .def_property_readonly(
          "contact_wrench", [](const MomentumObserver& o) { return Vector6d(o.contact_wrench()); },
          "contact-only wrench estimate, world axes about E's origin, [f; τ] (6,) [N, N·m]");
}

}  // namespace mjarm::python
