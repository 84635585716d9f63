// 17_ompl_shelf_film: the Panda reaches from home into a cluttered shelf (the scene of
// `mjarm bench ompl`: three levels, two columns, three boxes in every cell). OMPL's RRT-Connect
// plans in joint space around the shelf with MuJoCo's collision detection, the path is timed as
// fast as the joint limits allow (TOPP-RA), and operational-space control tracks it in
// simulation while a camera films it. Prints the plan and the tracking figures; exits 0 only when
// the plan and its timing succeed, the tool ends within 5 mm of the goal and the arm touched
// nothing on the way. The video goes to the first argument (default 17_ompl_shelf_film.mp4).

#include <Eigen/Geometry>
#include <cstdio>
#include <exception>
#include <memory>
#include <numbers>

#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/planning/collision_checker.hpp"
#include "mjarm/planning/ompl_benchmark.hpp"
#include "mjarm/planning/ompl_planner.hpp"
#include "mjarm/planning/planned_reference.hpp"
#include "mjarm/render/frame_schedule.hpp"
#include "mjarm/render/offscreen_renderer.hpp"
#include "mjarm/render/video_writer.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"

int main(int argc, char** argv) try {
  const char* out = argc > 1 ? argv[1] : "17_ompl_shelf_film.mp4";
  const mjarm::Robot robot = mjarm::shelf_benchmark_scene();
  const mjarm::Chain chain(robot, "attachment_site");
  const std::vector<double> home = robot.keyframe_qpos("home");
  const Eigen::VectorXd q_home = chain.gather(home.data());

  // the goal: the tool 10 cm into the middle level's left cell, pointing into the shelf (+x),
  // between the cell's clutter
  mjarm::PoseGoal goal;
  goal.X_WT.R =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  goal.X_WT.p = {0.55, 0.225, 0.47};

  mjarm::OmplOptions options;  // RRT-Connect, seed 1, simplified, timed time-optimally
  options.time_budget = 10.0;  // an upper bound: RRT-Connect stops at its first path
  mjarm::OmplPlanner planner(chain, options);
  const mjarm::OmplResult plan = planner.plan(q_home, goal);
  std::printf("plan: %s — %s\n", mjarm::to_string(plan.status), plan.message.c_str());
  if (!plan.ok() || !plan.time_optimal) return 1;
  std::printf("  %zu knots, %.2f rad, planned in %.1f ms with %lld validity checks\n",
              plan.path.size(), plan.path_length, plan.planning_time * 1e3,
              static_cast<long long>(plan.validity_checks));
  std::printf("  duration: %.2f s time-optimal, %.2f s as a blended spline\n",
              plan.time_optimal->duration(), plan.trajectory.duration());

  // tracked by operational-space control; filmed from the robot's left, looking into the shelf
  mjarm::Simulation sim(robot);
  const std::unique_ptr<mjarm::Controller> controller =
      mjarm::make_shelf_pick_controller("osc", chain, mjarm::shelf_pick_robot("panda"));
  sim.add_controller(*controller);
  sim.reset("home");
  mjarm::PlannedReference reference(chain, *plan.time_optimal, 0.5, 0.5 * sim.timestep());
  const auto camera = mjarm::CameraSpec::free_camera({0.35, 0.05, 0.45}, 2.0, -60.0, -20.0);
  mjarm::OffscreenRenderer renderer(robot, 480, 360);
  mjarm::VideoWriter video(out, 480, 360, 15.0);
  mjarm::FrameSchedule frames(15.0, sim.time());
  mjarm::CollisionChecker contacts(chain);  // the arm against the shelf and the boxes
  int touching_ticks = 0;
  mjarm::TickResult tick;
  do {
    tick = sim.tick(reference);
    if (!contacts.valid(chain.gather(sim.data().qpos))) ++touching_ticks;
    for (int k = frames.frames_due(sim.time()); k > 0; --k)
      video.write(renderer.render(sim.data(), camera));
  } while (tick.ok());  // until the reference has ended (finished) or a fault
  video.close();

  const mjarm::TrackingError& e = reference.tracking();
  const Eigen::Vector3d p_end =
      mjarm::ChainKinematics(chain).update(chain.gather(sim.data().qpos)).p;
  const double miss = (p_end - goal.X_WT.p).norm();
  std::printf(
      "tracked by OSC: %s; position error max %.2f mm, RMS %.2f mm; the tool ends %.2f mm "
      "from the goal; ticks touching the shelf: %d\n",
      mjarm::to_string(tick.status), e.max_position * 1e3, e.rms_position * 1e3, miss * 1e3,
      touching_ticks);
  std::printf("wrote %s (%lld frames)\n", out, static_cast<long long>(video.frames()));
  const bool ok = tick.status == mjarm::TickStatus::finished && miss < 0.005 &&
                  touching_ticks == 0 && video.complete();
  std::printf("%s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "17_ompl_shelf_film: %s\n", e.what());
  return 1;
}
