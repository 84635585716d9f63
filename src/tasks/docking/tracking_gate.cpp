#include "mjarm/tasks/docking/tracking_gate.hpp"

#include <cmath>
#include <numbers>

#include "mjarm/error.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/docking/task.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "tasks/torque_run_loop.hpp"

namespace mjarm {

namespace {

/// φ, φ̇, φ̈ of one loop at @p t: the speed ω·smootherstep ramps in over T_r, holds, ramps out;
/// the loop covers 2π in T = 1/f + T_r.
std::array<double, 3> loop_phase(const TrackingGateOptions& o, double t) noexcept {
  const double w = 2.0 * std::numbers::pi * o.frequency;
  const double Tr = o.ramp_time;
  const double Tc = 1.0 / o.frequency - Tr;  // cruise
  // ∫₀ˣ smootherstep = x⁶ − 3x⁵ + 2.5x⁴ (½ at x = 1)
  auto area = [](double x) { return x * x * x * x * (x * x - 3.0 * x + 2.5); };
  if (t <= 0.0) return {0.0, 0.0, 0.0};
  if (t < Tr) {
    const RampSample s = smootherstep(t / Tr);
    return {w * Tr * area(t / Tr), w * s.s, w * s.ds / Tr};
  }
  if (t < Tr + Tc) return {w * (0.5 * Tr + (t - Tr)), w, 0.0};
  if (t < 2.0 * Tr + Tc) {
    const double x = (t - Tr - Tc) / Tr;
    const RampSample s = smootherstep(x);
    return {w * (0.5 * Tr + Tc + Tr * (x - area(x))), w * (1.0 - s.s), -w * s.ds / Tr};
  }
  return {2.0 * std::numbers::pi, 0.0, 0.0};
}

void add(TrackingErrors& e, double position, double angle) {
  ++e.samples;
  e.position_rms += position * position;  // sums of squares until `finish`
  e.orientation_rms += angle * angle;
  e.max_position = std::max(e.max_position, position);
  e.max_orientation = std::max(e.max_orientation, angle);
}

void finish(TrackingErrors& e) {
  if (e.samples == 0) return;
  e.position_rms = std::sqrt(e.position_rms / e.samples);
  e.orientation_rms = std::sqrt(e.orientation_rms / e.samples);
}

/// The gate as a reference source (the null-space posture is the start configuration).
class GateSource final : public ReferenceSource {
 public:
  GateSource(const TrackingGateOptions& o, const Pose& X_start, const Eigen::VectorXd& q_start,
             double velocity_lag)
      : options_(o), X_start_(X_start), q_start_(q_start), lag_(velocity_lag) {}
  bool update(const mjData& data, Reference& reference) noexcept override {
    if (!started_) {
      t0_ = data.time;
      started_ = true;
    }
    t_ = data.time - t0_;
    if (t_ >= tracking_gate_duration(options_) - 1e-9) return false;
    const Se3Interpolation::Sample now = tracking_gate_reference(options_, X_start_, t_);
    const Se3Interpolation::Sample lagged =
        tracking_gate_reference(options_, X_start_, std::max(0.0, t_ - lag_));
    reference.task.X_WE = now.X_WE;
    reference.task.V_WE = lagged.V_WE;
    reference.task.A_WE = now.A_WE;
    reference.task.F_ext.setZero();
    reference.joint.hold(q_start_);
    X_WD_ = now.X_WE;
    return true;
  }
  const Pose& reference_pose() const noexcept { return X_WD_; }
  double time() const noexcept { return t_; }

 private:
  TrackingGateOptions options_;
  Pose X_start_;
  Eigen::VectorXd q_start_;
  double lag_;
  bool started_ = false;
  double t0_ = 0.0, t_ = 0.0;
  Pose X_WD_;
};

}  // namespace

void check(const TrackingGateOptions& o) {
  check_fields(o);
  if (!(o.ramp_time < 1.0 / o.frequency))
    throw Error("tracking gate: ramp_time (" + number_text(o.ramp_time) +
                " s) must be shorter than a loop at cruise, 1/frequency = " +
                number_text(1.0 / o.frequency) + " s");
  if (!(o.radius < o.height + 0.02))
    throw Error(
        "tracking gate: the figure-eight would dip into the socket (radius/2 must stay "
        "above the socket's top: radius < height)");
}

double tracking_gate_duration(const TrackingGateOptions& o) noexcept {
  return 2.0 * (1.0 / o.frequency + o.ramp_time) + o.settle_time;
}

Se3Interpolation::Sample tracking_gate_reference(const TrackingGateOptions& o, const Pose& X_start,
                                                 double t) noexcept {
  Se3Interpolation::Sample s;
  s.X_WE = X_start;
  const double loop = 1.0 / o.frequency + o.ramp_time;
  const bool eight = t >= loop;
  const auto [phi, dphi, ddphi] = loop_phase(o, eight ? t - loop : t);
  if (eight && t >= 2.0 * loop) return s;
  const double r = o.radius;
  // p(φ) − c, p′(φ), p″(φ) in (y, z)
  Eigen::Vector3d p, dp, ddp;
  if (!eight) {
    p << 0.0, r * std::sin(phi), r * (1.0 - std::cos(phi));
    dp << 0.0, r * std::cos(phi), r * std::sin(phi);
    ddp << 0.0, -r * std::sin(phi), r * std::cos(phi);
  } else {
    p << 0.0, r * std::sin(phi), 0.5 * r * std::sin(2.0 * phi);
    dp << 0.0, r * std::cos(phi), r * std::cos(2.0 * phi);
    ddp << 0.0, -r * std::sin(phi), -2.0 * r * std::sin(2.0 * phi);
  }
  s.X_WE.p = X_start.p + p;
  s.V_WE.head<3>() = dp * dphi;
  s.A_WE.head<3>() = ddp * dphi * dphi + dp * ddphi;
  return s;
}

bool passes(const TrackingGateReport& report, const TrackingGateTargets& targets) noexcept {
  return report.ok() && report.total.position_rms <= targets.position_rms &&
         report.total.orientation_rms <= targets.orientation_rms;
}

TrackingGateReport run_tracking_gate(const TrackingGateOptions& options) {
  check(options);
  check(options.controller);
  const std::shared_ptr<const DockingScene> scene =
      shared_docking_scene(options.scene, options.joint_friction);
  TrackingGateReport report;
  report.controller = to_string(options.controller.law);
  report.source = options.controller.source;
  // the start point c: the tip above the socket, the peg pointing down
  const DockingGeometry& g = scene->options.geometry;
  report.X_start = scene->seated();
  report.X_start.p += (g.chamfer + g.bore_depth + options.height) * scene->options.X_WS.R.col(2);
  const Robot& robot = scene->robot;
  const Eigen::VectorXd q_start = docking_start_configuration(*scene, report.X_start);
  Simulation sim(robot, torque_run::torque_simulation(options.max_acceleration));
  DockingControllerOptions controller_options = options.controller;
  controller_options.control_period = sim.control_period();
  DockingController controller(*scene, controller_options);
  sim.add_controller(controller);
  std::vector<double> qpos(static_cast<std::size_t>(robot.nq()), 0.0);
  scene->chain.scatter(q_start, qpos.data());
  sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(robot.nv()), 0.0));
  torque_run::start_held(sim, scene->chain);
  GateSource source(options, report.X_start, q_start, sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep());

  const int tip = robot.site(DockingNames::tip);
  const double loop = 1.0 / options.frequency + options.ramp_time;
  report.run = torque_run::run_ticks(sim, source, nullptr, "gate", [&] {
    // the step just taken: kinematics and contacts of its start state, the tick's reference
    const mjData& d = sim.data();
    if (d.ncon > 0) ++report.contact_ticks;
    const Eigen::Map<const Eigen::Vector3d> p(d.site_xpos + 3 * tip);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d.site_xmat + 9 * tip);
    const Pose& X_ref = source.reference_pose();
    const double position = (p - X_ref.p).norm();
    const double angle = so3::angle(X_ref.R.transpose() * R);
    add(source.time() < loop ? report.loops[0] : report.loops[1], position, angle);
    add(report.total, position, angle);
  });
  for (TrackingErrors& e : report.loops) finish(e);
  finish(report.total);
  return report;
}

}  // namespace mjarm
