#include "mjarm/tasks/planned_motion.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "mjarm/sim/simulation.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"

namespace mjarm {

namespace {

/// The plan's reference, which also notes the robot's contacts at the start of every tick (the
/// contact list `update` sees is that of the tick's state).
class ContactWatchingReference final : public ReferenceSource {
 public:
  ContactWatchingReference(PlannedReference& reference, const Chain& chain)
      : reference_(reference), contacts_(chain) {}

  bool update(const mjData& data, Reference& reference) noexcept override {
    const RobotContact c = contacts_.deepest(data, 0.0);
    if (c.found()) {
      if (seen_.ticks++ == 0) {
        seen_.first_time = data.time;
        seen_.first = c;
      }
      if (c.distance < seen_.deepest.distance) seen_.deepest = c;
    }
    return reference_.update(data, reference);
  }

  /// What was seen, with the first pair named.
  TrackingContacts seen() const {
    TrackingContacts out = seen_;
    if (out.any())
      out.first_pair =
          contacts_.geom_name(out.first.geom1) + " and " + contacts_.geom_name(out.first.geom2);
    return out;
  }

 private:
  PlannedReference& reference_;
  RobotContacts contacts_;
  TrackingContacts seen_;
};

}  // namespace

PlannedMotionWorld planned_motion_world(const ShelfPickRobot& robot,
                                        const std::filesystem::path& scene) {
  if (scene.empty()) return {Robot::bundled(robot.model), robot.frame};
  Scene world = load_scene_file(scene);
  RobotSpec spec;
  spec.name = robot.name;
  spec.model = robot.model;
  try {
    world.add_robot(spec);
  } catch (const Error& e) {
    throw Error("planned motion: the robot " + robot.name + " (" + robot.model +
                ") cannot join the scene file " + scene.string() +
                ", whose world it is placed in: " + e.what());
  }
  return {world.compile(), robot.name + "/" + robot.frame};
}

PlannedMotionRun track_planned_motion(const Chain& chain, const ShelfPickRobot& robot,
                                      const Eigen::VectorXd& start_qpos,
                                      const JointSpline& trajectory,
                                      const TrackingOptions& options) {
  check_shelf_pick_controller(options.controller);
  if (!(options.settle_time >= 0.0))
    throw Error("planned motion: the settle time must be ≥ 0 [s], got " +
                std::to_string(options.settle_time));
  SimulationOptions sim_options;
  sim_options.mode = SimulationMode::torque;
  sim_options.control_period = options.control_period;
  sim_options.max_acceleration = options.max_acceleration;
  Simulation sim(chain.robot(), sim_options);
  const std::unique_ptr<Controller> controller =
      make_shelf_pick_controller(options.controller, chain, robot);
  sim.add_controller(*controller);
  const std::vector<double> qpos(start_qpos.data(), start_qpos.data() + start_qpos.size());
  sim.set_state(qpos, std::vector<double>(static_cast<std::size_t>(chain.robot().nv()), 0.0));
  PlannedReference plan(chain, trajectory, options.settle_time,
                        sim.uses_rk4() ? 0.0 : 0.5 * sim.timestep());
  ContactWatchingReference source(plan, chain);
  PlannedMotionRun out;
  out.run = sim.run(source, plan.run_time() + 1.0);
  out.tracking = plan.tracking();
  out.contacts = source.seen();
  out.control_period = sim.control_period();
  return out;
}

PlannedMotionReport run_planned_motion(const PlannedMotionOptions& options) {
  const ShelfPickRobot& robot = shelf_pick_robot(options.robot);
  check_shelf_pick_controller(options.tracking.controller);
  const PlannedMotionWorld world = planned_motion_world(robot, options.scene);
  const Robot& model = world.model;
  const Chain chain(model, world.frame);
  const std::vector<std::string> keys = model.keyframe_names();
  Eigen::VectorXd start = Eigen::Map<const Eigen::VectorXd>(model.model().qpos0, model.model().nq);
  if (std::find(keys.begin(), keys.end(), "home") != keys.end()) {
    const std::vector<double> home = model.keyframe_qpos("home");
    start = Eigen::Map<const Eigen::VectorXd>(home.data(), static_cast<Eigen::Index>(home.size()));
  }
  PlanOptions plan_options;
  plan_options.seed = options.seed;
  plan_options.checks.min_singular_value = options.min_sigma;
  PlannedMotionReport report;
  report.robot = robot.name;
  report.plan = plan_waypoint_path(chain, start, load_waypoints(options.waypoints), plan_options);
  if (report.planned())
    report.tracked =
        track_planned_motion(chain, robot, start, report.plan.result.trajectory, options.tracking);
  return report;
}

}  // namespace mjarm
