#include "mjarm/tasks/approach_timing.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/trajectory/smoothstep.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

/// Largest ratio (dynamic torque) / (allowed dynamic torque) over the move of duration @p T.
double worst_ratio(const Chain& chain, mjData* d, std::span<const double> qpos_start,
                   const Eigen::VectorXd& q_start, const Eigen::VectorXd& dq, double T,
                   const std::vector<double>& allowed) {
  const mjModel& m = chain.robot().model();
  const SmoothRamp profile(SmoothRamp::Kind::smootherstep, T);  // the minimum-jerk scaling
  const int n = chain.size();
  double worst = 0.0;
  constexpr int kSamples = 64;
  for (int k = 0; k <= kSamples; ++k) {
    const RampSample s = profile.at(T * k / kSamples);
    std::copy(qpos_start.begin(), qpos_start.end(), d->qpos);
    chain.scatter(q_start + s.s * dq, d->qpos);
    // at rest first: gravity (and springs) alone
    mju_zero(d->qvel, m.nv);
    mju_zero(d->qacc, m.nv);
    mj_inverse(&m, d);
    Eigen::VectorXd rest(n);
    for (int i = 0; i < n; ++i) rest[i] = d->qfrc_inverse[chain.dof_address(i)];
    for (int i = 0; i < n; ++i) {
      d->qvel[chain.dof_address(i)] = s.ds * dq[i];
      d->qacc[chain.dof_address(i)] = s.dds * dq[i];
    }
    mj_inverse(&m, d);
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(allowed[i])) continue;
      const double room = allowed[i] - std::abs(rest[i]);
      if (room <= 0.0)
        throw Error("torque_feasible_duration: joint '" + chain.joint_names()[i] +
                    "' needs " + number_text(std::abs(rest[i])) +
                    " N·m at rest on the way, more than the allowed " +
                    number_text(allowed[i]));
      worst = std::max(worst, std::abs(d->qfrc_inverse[chain.dof_address(i)] - rest[i]) / room);
    }
  }
  return worst;
}

}  // namespace

double torque_feasible_duration(const Chain& chain, std::span<const double> qpos_start,
                                const Eigen::Ref<const Eigen::VectorXd>& q_target, double duration,
                                double torque_fraction) {
  const Robot& robot = chain.robot();
  if (qpos_start.size() != static_cast<std::size_t>(robot.nq()))
    throw Error("torque_feasible_duration: qpos_start needs " + std::to_string(robot.nq()) +
                " values, got " + std::to_string(qpos_start.size()));
  for (double v : qpos_start)
    if (!std::isfinite(v)) throw Error("torque_feasible_duration: qpos_start holds NaN/inf");
  chain.check(q_target, "q_target");
  if (!(duration > 0.0) || !std::isfinite(duration))
    throw Error("torque_feasible_duration: duration must be positive and finite [s]");
  if (!(torque_fraction > 0.0 && torque_fraction <= 1.0))
    throw Error("torque_feasible_duration: torque_fraction must be in (0, 1], got " +
                number_text(torque_fraction));

  const int n = chain.size();
  std::vector<double> allowed(n);
  for (int i = 0; i < n; ++i) allowed[i] = torque_fraction * joint_torque_limit(chain, i);
  const Eigen::VectorXd q_start = chain.gather(qpos_start.data());
  const Eigen::VectorXd dq = q_target - q_start;
  DataPtr data = robot.make_data();
  double T = duration;
  // τ_dyn ∝ 1/T²: one rescale lands close; a second pass absorbs the passive (∝ 1/T) part
  for (int pass = 0; pass < 3; ++pass) {
    const double ratio = worst_ratio(chain, data.get(), qpos_start, q_start, dq, T, allowed);
    if (ratio <= 1.0) break;
    T *= std::sqrt(ratio) * (pass == 0 ? 1.0 : 1.01);
  }
  return T;
}

}  // namespace mjarm
