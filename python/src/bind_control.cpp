// control room: Reference, the Controller interface (subclassable in Python), every controller.
#include "bindings.hpp"
#include "controller_step.hpp"
#include "declared_fields.hpp"
#include "mjarm/control/acceleration_control.hpp"
#include "mjarm/control/cartesian_impedance.hpp"
#include "mjarm/control/computed_torque.hpp"
#include "mjarm/control/gravity_compensation.hpp"
#include "mjarm/control/gripper_pd.hpp"
#include "mjarm/control/hqp_ac.hpp"
#include "mjarm/control/joint_pd.hpp"
#include "mjarm/control/operational_space.hpp"
#include "mjarm/control/se3_impedance.hpp"
#include "mjarm/control/task_pd.hpp"
#include "mjarm/control/wrench_source.hpp"
#include "python_controller.hpp"

namespace mjarm::python {
namespace {

template <typename C, typename O>
void controller_class(py::module_& m, const char* name, const char* doc) {
  auto cls = py::class_<C, Controller>(m, name, doc);
  cls.def(py::init<const Chain&, const O&>(), py::arg("chain"), py::arg("options") = O{})
      .def_property_readonly(
          "options", [](const C& c) { return c.options(); }, "the controller's options");
  bind_compute<C>(cls);
}

/// A Python class of declared options @p O: a default constructor and every declared field.
template <typename O>
py::class_<O> options_class(py::module_& m, const char* name) {
  auto cls = py::class_<O>(m, name);
  cls.def(py::init<>());
  def_fields(cls);
  return cls;
}

}  // namespace

void bind_control(py::module_& m) {
  def_enum<CommandKind>(m, "CommandKind", "What a controller's output means.");
  def_enum<TaskMode>(m, "TaskMode");
  def_enum<BiasTerm>(m, "BiasTerm");

  auto joint =
      py::class_<JointReference>(m, "JointReference", "Desired joint motion (chain order).");
  joint.def(py::init<>());
  vector_property<JointReference>(joint, "q", &JointReference::q, "position (n,) [rad or m]");
  vector_property<JointReference>(joint, "qd", &JointReference::qd, "velocity (n,) [rad/s or m/s]");
  vector_property<JointReference>(joint, "qdd", &JointReference::qdd,
                                  "acceleration (n,) [rad/s² or m/s²]");
  auto task =
      py::class_<TaskReference>(m, "TaskReference", "Desired motion of the frame E, world axes.");
  task.def(py::init<>())
      .def_property(
          "X_WE", [](const TaskReference& t) { return t.X_WE; },
          [](TaskReference& t, py::handle X) { t.X_WE = to_pose(X, "X_WE"); }, "desired pose");
  fixed_property<TaskReference>(task, "V_WE", &TaskReference::V_WE, "desired twist (6,)");
  fixed_property<TaskReference>(task, "A_WE", &TaskReference::A_WE, "desired acceleration (6,)");
  fixed_property<TaskReference>(task, "F_ext", &TaskReference::F_ext, "desired wrench (6,)");
  py::class_<Reference>(m, "Reference", "What a controller tracks this tick.")
      .def(py::init<>())
      .def_readwrite("joint", &Reference::joint, "the joint-space reference (q, q̇, q̈)")
      .def_readwrite("task", &Reference::task,
                     "the task-space reference (pose, twist, acceleration, wrench)")
      .def_readwrite("gripper", &Reference::gripper, "0 open .. 1 closed")
      .def("copy", [](const Reference& r) { return r; });

  py::class_<Controller, PyController>(
      m, "Controller",
      "One control law. Subclass it in Python: call Controller.__init__(self, chain, kind, name) "
      "and define compute(self, data, reference) -> ndarray (n,) (torques or position targets in "
      "chain order); optionally reset(self). The simulation calls it every control tick; an "
      "exception it raises stops the run and is raised by Simulation.tick/run.")
      .def(py::init<const Chain&, CommandKind, std::string>(), py::arg("chain"),
           py::arg("kind") = CommandKind::torque, py::arg("name") = "python")
      .def_property_readonly(
          "name", [](const Controller& c) { return std::string(c.name()); },
          "short identifier, e.g. \"osc\", \"ct\", \"joint-pd\"")
      .def_property_readonly("command_kind", &Controller::command_kind,
                             "whether compute writes torques or position targets")
      .def_property_readonly("chain", &Controller::chain, "the chain this controller commands")
      .def_property_readonly(
          "compensates_bias", &Controller::compensates_bias,
          "True when the commands already cancel the bias forces (gravity, possibly Coriolis)")
      .def("reset", &Controller::reset, "forgets integrators and filters")
      .def_property_readonly(
          "internal_names",
          [](const Controller& c) {
            const auto s = c.internal_names();
            return std::vector<std::string>(s.begin(), s.end());
          },
          "names of the internals a recorder logs each tick")
      .def_property_readonly(
          "internal_values",
          [](const Controller& c) {
            const auto s = c.internal_values();
            return to_array(s.data(), static_cast<Eigen::Index>(s.size()));
          },
          "values of those internals from the last compute, in internal_names order "
          "(len(internal_names),)")
      .def(
          "compute",
          [](Controller& c, const DataHandle& d, const Reference& reference, py::handle out) {
            return controller_step(c, d, reference, out);
          },
          py::arg("data"), py::arg("reference"), py::arg("out") = py::none(), kComputeDoc);

  auto gains = py::class_<JointPdGains>(m, "JointPdGains", "Per-joint (or uniform, size 1) gains.");
  gains.def(py::init<>())
      .def_static("uniform", &JointPdGains::uniform, py::arg("kp"), py::arg("kd"))
      .def_static("critically_damped", &JointPdGains::critically_damped, py::arg("omega"));
  def_fields(gains);

  options_class<JointPdOptions>(m, "JointPdOptions");
  auto joint_pd = py::class_<JointPdController, Controller>(m, "JointPdController",
                                                            "Joint PD + gravity (torque).");
  joint_pd
      .def(py::init<const Chain&, const JointPdOptions&>(), py::arg("chain"),
           py::arg("options") = JointPdOptions{})
      .def_property_readonly("gains", &JointPdController::gains, "the gains, one entry per joint");
  bind_compute<JointPdController>(joint_pd);
  auto gravity_servo = py::class_<GravityCompensationController, Controller>(
      m, "GravityCompensationController",
      "Servo targets offset to cancel gravity (position mode).");
  gravity_servo.def(py::init<const Chain&, BiasTerm>(), py::arg("chain"),
                    py::arg("term") = BiasTerm::gravity);
  bind_compute<GravityCompensationController>(gravity_servo);
  auto gravity_hold = py::class_<GravityHoldController, Controller>(
      m, "GravityHoldController", "Torques that cancel gravity (torque mode).");
  gravity_hold.def(py::init<const Chain&, BiasTerm>(), py::arg("chain"),
                   py::arg("term") = BiasTerm::gravity);
  bind_compute<GravityHoldController>(gravity_hold);

  options_class<ComputedTorqueOptions>(m, "ComputedTorqueOptions");
  auto computed_torque = py::class_<ComputedTorqueController, Controller>(
      m, "ComputedTorqueController", "tau = M (qdd_d + PD) + h.");
  computed_torque.def(py::init<const Chain&, const ComputedTorqueOptions&>(), py::arg("chain"),
                      py::arg("options") = ComputedTorqueOptions{});
  bind_compute<ComputedTorqueController>(computed_torque);

  options_class<TaskPdOptions>(m, "TaskPdOptions");
  controller_class<TaskPdController, TaskPdOptions>(m, "TaskPdController",
                                                    "tau = J^T (K e + D ė) + g.");

  options_class<AccelerationControlOptions>(m, "AccelerationControlOptions");
  controller_class<AccelerationController, AccelerationControlOptions>(
      m, "AccelerationController",
      "Resolved task acceleration through damped J^+, then M qdd + h.");

  options_class<JointLimitOptions>(m, "JointLimitOptions");  // nested in osc, cic and se3
  options_class<OperationalSpaceOptions>(m, "OperationalSpaceOptions");
  auto osc_controller = py::class_<OperationalSpaceController, Controller>(
      m, "OperationalSpaceController", "Operational-space impedance (osc).");
  osc_controller
      .def(py::init<const Chain&, const OperationalSpaceOptions&>(), py::arg("chain"),
           py::arg("options") = OperationalSpaceOptions{})
      .def_property_readonly("options", &OperationalSpaceController::options,
                             "the controller's options")
      .def(
          "set_measured_wrench",
          [](OperationalSpaceController& c, py::handle F) {
            c.set_measured_wrench(to_fixed<6>(F, "F_W"));
          },
          py::arg("F_W"))
      .def_property_readonly(
          "integral", [](const OperationalSpaceController& c) { return Vector6d(c.integral()); },
          "∫e dt after the last compute, first m entries used (6,) [m·s, rad·s]")
      .def_property_readonly(
          "task_force",
          [](const OperationalSpaceController& c) { return Vector6d(c.task_force()); },
          "task-space force F of the last compute, first m entries used (6,) [N, N·m]");
  bind_compute<OperationalSpaceController>(osc_controller);

  options_class<StiffnessRelease>(m, "StiffnessRelease")
      .def_readwrite("axes", &StiffnessRelease::axes,
                     "the λ axes [x, y, z, rx, ry, rz] (E's own axes) whose stiffness goes to zero "
                     "on contact (6,)");
  auto se3o = options_class<Se3ImpedanceOptions>(m, "Se3ImpedanceOptions");
  fixed_property<Se3ImpedanceOptions>(
      se3o, "inertia", &Se3ImpedanceOptions::inertia,
      "desired apparent inertia A, symmetric positive definite (6, 6) [kg; kg·m²]");
  fixed_property<Se3ImpedanceOptions>(
      se3o, "damping", &Se3ImpedanceOptions::damping,
      "damping D, symmetric positive definite (6, 6) [N·s/m; N·m·s/rad]");
  fixed_property<Se3ImpedanceOptions>(
      se3o, "stiffness", &Se3ImpedanceOptions::stiffness,
      "stiffness K, symmetric positive semi-definite (6, 6) [N/m; N·m/rad]");
  def_enum<Se3ImpedanceStatus>(m, "Se3ImpedanceStatus");
  auto se3_controller = py::class_<Se3ImpedanceController, Controller>(
      m, "Se3ImpedanceController", "SE(3) Lie-group impedance (full 6x6 A, D, K).");
  se3_controller
      .def(py::init<const Chain&, const Se3ImpedanceOptions&>(), py::arg("chain"),
           py::arg("options") = Se3ImpedanceOptions{})
      .def_property_readonly("options", &Se3ImpedanceController::options,
                             "the controller's options")
      .def_property_readonly("status", &Se3ImpedanceController::status,
                             "status of the last compute")
      .def_property_readonly(
          "error", [](const Se3ImpedanceController& c) { return Vector6d(c.error()); },
          "λ = log(X_EW·X_WD) at the last compute (6,) [m, rad]")
      .def(
          "set_measured_wrench",
          [](Se3ImpedanceController& c, py::handle F) {
            c.set_measured_wrench(to_fixed<6>(F, "F_E"));
          },
          py::arg("F_E"))
      .def("start_release", &Se3ImpedanceController::start_release, py::arg("time"));
  bind_compute<Se3ImpedanceController>(se3_controller);

  def_enum<WrenchSourceKind>(m, "WrenchSourceKind");
  options_class<WrenchSourceOptions>(m, "WrenchSourceOptions")
      .def_readwrite("observer", &WrenchSourceOptions::observer,
                     "observer: its gains and Coriolis method");
  def_enum<CicInertia>(m, "CicInertia");
  def_enum<CicIntegral>(m, "CicIntegral");
  options_class<CartesianImpedanceOptions>(m, "CartesianImpedanceOptions");
  auto cic_controller = py::class_<CartesianImpedanceController, Controller>(
      m, "CartesianImpedanceController", "Cartesian impedance with a measured wrench (CIC).");
  cic_controller.def(py::init<const Chain&, const CartesianImpedanceOptions&>(), py::arg("chain"),
                     py::arg("options") = CartesianImpedanceOptions{});
  bind_compute<CartesianImpedanceController>(cic_controller);

  auto compliance = options_class<AdaptiveComplianceOptions>(m, "AdaptiveComplianceOptions");
  fixed_property<AdaptiveComplianceOptions>(
      compliance, "stiffness", &AdaptiveComplianceOptions::stiffness,
      "nominal task stiffness K0, symmetric positive definite (6, 6) [N/m; N·m/rad]");
  options_class<HqpAcPreload>(m, "HqpAcPreload");
  options_class<HqpAcOptions>(m, "HqpAcOptions");
  def_enum<HqpAcStatus>(m, "HqpAcStatus");
  auto hqp_controller = py::class_<HqpAcController, Controller>(
      m, "HqpAcController", "HQP-AC: adaptive compliance, two QPs under hard bounds.");
  hqp_controller
      .def(py::init<const Chain&, const HqpAcOptions&>(), py::arg("chain"),
           py::arg("options") = HqpAcOptions{})
      .def_property_readonly("status", &HqpAcController::status, "status of the last compute")
      .def_property_readonly(
          "acceleration",
          [](const HqpAcController& c) { return Eigen::VectorXd(c.acceleration()); },
          "commanded joint acceleration q̈ of the last compute (n,) [rad/s²]");
  bind_compute<HqpAcController>(hqp_controller);

  options_class<GripperPdOptions>(m, "GripperPdOptions");
  auto gripper_controller = py::class_<GripperPdController, Controller>(
      m, "GripperPdController", "Fingers follow reference.gripper (0 open, 1 closed).");
  gripper_controller
      .def(py::init<const Chain&, const GripperPdOptions&>(), py::arg("fingers"),
           py::arg("options") = GripperPdOptions{})
      .def_property_readonly(
          "open", [](const GripperPdController& c) { return Eigen::VectorXd(c.open()); },
          "finger positions at fraction 0 (n,) [m or rad]")
      .def_property_readonly(
          "closed", [](const GripperPdController& c) { return Eigen::VectorXd(c.closed()); },
          "finger positions at fraction 1 (n,) [m or rad]");
  bind_compute<GripperPdController>(gripper_controller);

  m.def(
      "task_error",
      [](py::handle a, py::handle b) { return task_error(to_pose(a, "X_WE"), to_pose(b, "X_WD")); },
      py::arg("X_WE"), py::arg("X_WD"), "task-space error (6,) world axes, linear first");
}

}  // namespace mjarm::python
