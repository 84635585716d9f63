// 11_target_filter: the reference the viewer's arm tracks when a slider jumps. A pose target
// jumps 0.3 m away; 0.4 s later, mid-motion, it jumps again to the other side. The target filter
// (the jerk-limited generator, recalculated from the current state at each jump) turns both
// jumps into one smooth motion: it prints the reference every 0.1 s and checks that the velocity
// never exceeded its limit and did not jump when the target did.

#include <cmath>
#include <cstdio>

#include "mjarm/lie/so3.hpp"
#include "mjarm/trajectory/target_filter.hpp"

int main() {
  mjarm::TargetFilter filter;  // 0.5 m/s, 2 m/s², 20 m/s³ per axis; 1.5 rad/s, 6, 60 for φ
  mjarm::Pose start;
  start.R = mjarm::so3::exp(Eigen::Vector3d(3.14, 0.0, 0.0));  // a tool pointing down
  start.p << 0.3, 0.0, 0.5;
  filter.reset(start);

  mjarm::Pose first = start, second = start;
  first.p << 0.6, 0.0, 0.5;   // 0.3 m along +x
  second.p << 0.3, 0.2, 0.4;  // then back and to the side, turned by 0.5 rad about z
  second.R = mjarm::so3::exp(Eigen::Vector3d(0.0, 0.0, 0.5)) * start.R;

  const double dt = 0.002;  // a 500 Hz control tick
  double peak_speed = 0.0, worst_step = 0.0;
  Eigen::Vector3d v_last = Eigen::Vector3d::Zero();
  std::printf("    t [s]   x [m]   y [m]   z [m]   vx [m/s]  vy [m/s]\n");
  for (int k = 1; k <= 750; ++k) {  // 1.5 s
    const mjarm::Pose& target = k * dt <= 0.4 ? first : second;
    const mjarm::Pose& X = filter.update(target, dt);
    const Eigen::Vector3d v = filter.velocity().head<3>();
    peak_speed = std::max(peak_speed, v.cwiseAbs().maxCoeff());
    worst_step = std::max(worst_step, (v - v_last).cwiseAbs().maxCoeff());  // per tick
    v_last = v;
    if (k % 50 == 0)
      std::printf("  %6.2f  %6.3f  %6.3f  %6.3f  %8.3f  %8.3f\n", k * dt, X.p.x(), X.p.y(), X.p.z(),
                  v.x(), v.y());
  }
  const bool arrived = filter.settled() && filter.pose().is_approx(second, 0.0);
  std::printf(
      "arrived exactly: %s; peak axis speed %.4f m/s (limit %.2f); largest change of "
      "velocity in one tick %.5f m/s (a_max·dt = %.5f)\n",
      arrived ? "yes" : "no", peak_speed, filter.limits().velocity, worst_step,
      filter.limits().acceleration * dt);
  const bool ok = arrived && peak_speed <= filter.limits().velocity * (1 + 1e-9) &&
                  worst_step <= filter.limits().acceleration * dt * (1 + 1e-9);
  return ok ? 0 : 1;
}
