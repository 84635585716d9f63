// Your own loop with a window on it: the UR5e built from its DH table sways through a slow
// joint-space motion under computed torque, in a plain mj_step1/mj_step2 loop that owns its
// mjData; a PassiveViewer draws it. Each iteration marks the tool's reference pose and plots the
// tracking error; double-click a link and Ctrl + right drag it to push the arm, and watch the
// controller pull it back (the "Your plots" and actuator figures show it).
//
//     example_16_passive_viewer           until the window is closed
//     example_16_passive_viewer 3         three simulated seconds, then the window closes
//
// Needs a display (or xvfb-run). Exits 0 when the loop ran and the window drew it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <thread>

#include "mjarm/control/computed_torque.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/model/dh_model.hpp"
#include "mjarm/teleop/passive_viewer.hpp"

int main(int argc, char** argv) {
  using namespace mjarm;
  constexpr double pi = std::numbers::pi;
  const double seconds = argc > 1 ? std::atof(argv[1]) : 0.0;  // 0: until the window closes
  DhArm arm;
  arm.name = "ur5e_dh";
  arm.links = {{.d = 0.1625, .alpha = pi / 2},
               {.a = -0.425},
               {.a = -0.3922},
               {.d = 0.1333, .alpha = pi / 2},
               {.d = 0.0997, .alpha = -pi / 2},
               {.d = 0.0996}};
  arm.effort = 150.0;
  arm.damping = 0.5;
  const Robot robot = dh_robot(arm);
  const mjModel& m = robot.model();
  DataPtr data = robot.make_data();
  mjData& d = *data;
  const Eigen::VectorXd q_home =
      (Eigen::VectorXd(6) << 0.0, -1.2, 1.4, -1.8, -1.57, 0.0).finished();
  Reference reference;
  reference.joint.hold(q_home);
  // the reference at time t: the first three joints sway about home (a slow Lissajous figure)
  const auto sway = [&](double t) {
    for (int i = 0; i < 3; ++i) {
      const double a = 0.3, phase = i * pi / 3, f = 0.8 * (1 + i * 0.5);
      reference.joint.q[i] = q_home[i] + a * std::sin(f * t + phase);
      reference.joint.qd[i] = a * f * std::cos(f * t + phase);
      reference.joint.qdd[i] = -a * f * f * std::sin(f * t + phase);
    }
  };
  sway(0.0);  // the arm starts on it
  for (int i = 0; i < 6; ++i) {
    d.qpos[i] = reference.joint.q[i];
    d.qvel[i] = reference.joint.qd[i];
  }
  mj_forward(&m, &d);

  const Chain chain(robot, "end");
  ComputedTorqueController law(chain);
  JointCommand command;
  command.value = Eigen::VectorXd::Zero(6);

  PassiveViewerOptions options;
  options.show_figures = true;
  options.camera = CameraSpec::free_camera(Eigen::Vector3d(0.0, 0.0, 0.4), 2.2, 135.0, -20.0);
  try {
    PassiveViewer viewer(robot, d, options);
    double worst_error = 0.0;
    const auto wall_start = std::chrono::steady_clock::now();
    while (viewer.running() && (seconds <= 0.0 || d.time < seconds)) {
      sway(d.time);
      mj_step1(&m, &d);
      law.compute(d, reference, command);
      for (int i = 0; i < 6; ++i) d.ctrl[i] = command.value[i];
      mj_step2(&m, &d);

      const Pose X_ref = forward_kinematics(chain, reference.joint.q);
      const Pose X_now = forward_kinematics(chain, chain.gather(d.qpos));
      const double error = (X_ref.p - X_now.p).norm();
      worst_error = std::max(worst_error, error);
      viewer.markers().add_frame(X_ref, 0.08);
      viewer.markers().add_text(X_ref.p + Eigen::Vector3d(0, 0, 0.06), "reference");
      viewer.plot("tool error [mm]", 1e3 * error);
      viewer.sync();
      // in step with the wall clock, so the motion is seen at its own pace
      std::this_thread::sleep_until(wall_start + std::chrono::duration<double>(d.time));
    }
    viewer.close();
    const ViewerReport report = viewer.report();
    std::printf(
        "%.2f s simulated, %lld states synced, %lld frames drawn, worst tool error "
        "%.2f mm; the window ended by: %s\n",
        d.time, static_cast<long long>(viewer.syncs()), static_cast<long long>(report.frames),
        1e3 * worst_error, report.ended_by.c_str());
    return viewer.syncs() > 0 && report.frames > 0 ? 0 : 1;
  } catch (const Error& e) {
    std::fprintf(stderr, "example_16_passive_viewer: %s\n", e.what());
    return 1;
  }
}
