// Planning a 5-waypoint path on the panda (torque-motor model, tool frame attachment_site) from
// the home keyframe, with the default PlanOptions: limits from the model (1 rad/s, accelerations
// from the actuators' torque limits), σmin ≥ 0.02, samples every 10 ms. Each iteration is one
// `WaypointPlanner::plan` (IK per waypoint, checks at every waypoint and ~400 samples with one
// mj_fwdPosition + mj_fwdVelocity each, the blended spline, its verification). Counters: the
// plan's duration [s] and the samples checked. A second case puts a box in the way of the first
// segment, so the planner tries other IK branches and a joint-space detour.
// The same path is timed against its target by `mjarm bench plan`.
// Run: build/bench_planning [--benchmark_min_time=2]

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/planning/motion_benchmark.hpp"
#include "mjarm/planning/waypoint_planner.hpp"

namespace {

const char* kBoxScene = R"(<mujoco model="panda_box">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="0.002"/>
  <include file="common/scene.xml"/>
  <include file="panda/panda_body.xml"/>
  <worldbody><geom name="obstacle" type="box" pos="0.47 0.10 0.45" size="0.035 0.035 0.035"/></worldbody>
  <actuator>
    <motor joint="joint1" ctrlrange="-87 87"/><motor joint="joint2" ctrlrange="-87 87"/>
    <motor joint="joint3" ctrlrange="-87 87"/><motor joint="joint4" ctrlrange="-87 87"/>
    <motor joint="joint5" ctrlrange="-12 12"/><motor joint="joint6" ctrlrange="-12 12"/>
    <motor joint="joint7" ctrlrange="-12 12"/>
  </actuator>
  <keyframe><key name="home" qpos="0 -0.785 0 -2.356 0 1.571 0.785"/></keyframe>
</mujoco>)";

void run(benchmark::State& state, const mjarm::Robot& robot) {
  const mjarm::Chain chain(robot, "attachment_site");
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q_home = chain.gather(home.data());
  mjarm::ChainKinematics fk(chain);
  const std::vector<mjarm::Pose> path = mjarm::motion_benchmark_waypoints(fk.update(q_home).R);
  mjarm::WaypointPlanner planner(chain);
  mjarm::PlanResult result;
  for (auto _ : state) {
    result = planner.plan(q_home, path);
    benchmark::DoNotOptimize(result);
  }
  if (!result.ok()) state.SkipWithError(result.message.c_str());
  state.counters["duration_s"] = result.trajectory.duration();
  state.counters["samples"] = static_cast<double>(result.samples);
}

void BM_PlanFiveWaypoints(benchmark::State& state) {
  run(state, mjarm::Robot::bundled("panda_torque"));
}
BENCHMARK(BM_PlanFiveWaypoints)->Unit(benchmark::kMillisecond);

void BM_PlanFiveWaypointsAroundABox(benchmark::State& state) {
  run(state, mjarm::Robot::from_string(kBoxScene, mjarm::Robot::models_dir()));
}
BENCHMARK(BM_PlanFiveWaypointsAroundABox)->Unit(benchmark::kMillisecond);

}  // namespace
