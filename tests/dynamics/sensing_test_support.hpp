#pragma once
// Shared helpers of the sensing tests (momentum observer, friction feed-forward): the iiwa14 in
// torque mode with chosen joint friction, and a split-step torque loop that runs an observer.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/dynamics/momentum_observer.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "support/files.hpp"

namespace mjarm::test {

/// The joint frictionloss of the Franka arm [N·m], used as a plausible set for the iiwa14.
inline const std::vector<double>& franka_frictionloss() {
  static const std::vector<double> f = {1.137, 1.137, 1.137, 1.137, 0.763, 0.44, 0.248};
  return f;
}

/// The MJCF of the bundled iiwa14_torque with frictionloss f[k] on joint k+1 (none when @p f is
/// empty), @p in_link7 inserted at the end of link7's body (e.g. a tool body) and @p sensors
/// as a <sensor> section; load it with `Robot::from_string(xml, Robot::models_dir())`.
inline std::string iiwa_torque_xml(const std::vector<double>& f, const std::string& in_link7 = "",
                                   const std::string& sensors = "") {
  const auto dir = Robot::models_dir();
  std::string main = slurp(dir / "iiwa14_torque.xml");
  std::string body = slurp(dir / "iiwa14" / "iiwa14_body.xml");
  body = body.substr(body.find("<mujoco>") + 8);
  body = body.substr(0, body.rfind("</mujoco>"));
  for (std::size_t k = 0; k < f.size(); ++k) {
    const std::string name = "name=\"joint" + std::to_string(k + 1) + "\"";
    body.replace(body.find(name), name.size(),
                 name + " frictionloss=\"" + std::to_string(f[k]) + "\"");
  }
  if (!in_link7.empty()) {
    const std::string site = "<site name=\"attachment_site\" pos=\"0 0 0.126\"/>";
    body.replace(body.find(site), site.size(), site + in_link7);
  }
  const std::string include = "<include file=\"iiwa14/iiwa14_body.xml\"/>";
  main.replace(main.find(include), include.size(), body);
  if (!sensors.empty()) {
    const std::string end = "</mujoco>";
    main.replace(main.rfind(end), end.size(), "<sensor>" + sensors + "</sensor>" + end);
  }
  return main;
}

/// The bundled iiwa14_torque with frictionloss f[k] on joint k+1 (none when @p f is empty).
inline Robot iiwa_torque_with_friction(const std::vector<double>& f) {
  return Robot::from_string(iiwa_torque_xml(f), Robot::models_dir());
}

/// A torque-mode run of a chain whose actuator i drives chain joint i: each physics step is
/// split (mj_step1, controller, observer, mj_step2), as `Simulation` does with Euler.
struct ObserverRig {
  const Chain& chain;
  DataPtr d;
  ChainDynamics dyn;
  MomentumObserver observer;
  Eigen::VectorXd tau;

  ObserverRig(const Chain& c, MomentumObserverOptions options = {})
      : chain(c),
        d(c.robot().make_data()),
        dyn(c),
        observer(c, options),
        tau(Eigen::VectorXd::Zero(c.size())) {}

  /// @p control(dyn, time, tau) writes the motor torques; @p each(rig) runs after every step.
  template <class Control, class Each>
  void run(int steps, Control control, Each each) {
    const mjModel& m = chain.robot().model();
    for (int k = 0; k < steps; ++k) {
      mj_step1(&m, d.get());
      dyn.update(*d);
      control(dyn, d->time, tau);
      for (int i = 0; i < chain.size(); ++i) {
        const double* range = m.actuator_ctrlrange + 2 * i;
        tau[i] = std::clamp(tau[i], range[0], range[1]);
        d->ctrl[i] = tau[i];
      }
      observer.update(*d, dyn, tau, m.opt.timestep);
      mj_step2(&m, d.get());
      each(*this);
    }
  }
};

}  // namespace mjarm::test
