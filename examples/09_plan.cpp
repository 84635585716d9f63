// 09_plan: plan a checked, timed joint trajectory for the bundled Panda through five Cartesian
// waypoints (tool pointing down as at home), print the per-waypoint checks, then track the plan
// in simulation with computed torque and print the tool's tracking error.
// Exits 0 only when the plan is ok and the tool stayed within 5 mm of its reference.

#include <cstdio>
#include <memory>

#include "mjarm/planning/planned_reference.hpp"
#include "mjarm/planning/waypoint_planner.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"

int main() {
  const mjarm::Robot robot = mjarm::Robot::bundled("panda_torque");
  const mjarm::Chain chain(robot, "attachment_site");
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q_home = chain.gather(home.data());

  // five positions, the orientation of the tool at home
  mjarm::ChainKinematics fk(chain);
  const Eigen::Matrix3d R_home = fk.update(q_home).R;
  std::vector<mjarm::Pose> path;
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.45, 0.0, 0.50), Eigen::Vector3d(0.45, 0.20, 0.40),
        Eigen::Vector3d(0.35, 0.25, 0.35), Eigen::Vector3d(0.30, 0.10, 0.45),
        Eigen::Vector3d(0.40, -0.15, 0.50)}) {
    mjarm::Pose X;
    X.R = R_home;
    X.p = p;
    path.push_back(X);
  }

  mjarm::WaypointPlanner planner(chain);  // limits from the model's actuators, 1 rad/s
  const mjarm::PlanResult plan = planner.plan(q_home, path);
  std::printf("plan: %s — %s\n", mjarm::to_string(plan.status), plan.message.c_str());
  for (const mjarm::WaypointReport& w : plan.waypoints)
    std::printf("  waypoint %d at %.3f s: sigma_min %.3f, max torque %.0f %% on the way, %s\n",
                w.index, w.time, w.check.sigma_min, 100.0 * w.max_torque_ratio, w.message.c_str());
  if (!plan.ok()) return 1;

  mjarm::Simulation sim(robot);
  const std::unique_ptr<mjarm::Controller> controller =
      mjarm::make_shelf_pick_controller("ct", chain, mjarm::shelf_pick_robot("panda"));
  sim.add_controller(*controller);
  sim.reset("home");
  mjarm::PlannedReference reference(chain, plan.trajectory, 0.5, 0.5 * sim.timestep());
  const mjarm::RunResult run = sim.run(reference, reference.run_time() + 1.0);
  const mjarm::TrackingError& e = reference.tracking();
  std::printf(
      "tracked by computed torque: %s; position error max %.3f mm, RMS %.3f mm, final "
      "%.3f mm\n",
      mjarm::to_string(run.status), e.max_position * 1e3, e.rms_position * 1e3,
      e.final_position * 1e3);
  return run.ok() && e.max_position < 0.005 ? 0 : 1;
}
