// `mjarm run plan ROBOT --waypoints FILE --controller NAME [--scene FILE]`: plans through the
// waypoints on the robot's torque-motor model (in a scene file's world of obstacles, if given) and
// tracks the plan in simulation under the chosen controller, reporting the tracking error of the
// tool frame and any contact the robot made (docs/planning.md).

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mjarm/error.hpp"
#include "mjarm/tasks/planned_motion.hpp"
#include "mjarm/tasks/shelf_pick/controllers.hpp"

namespace mjarm::cli {

namespace {

/// "none", or where the robot first touched something, how often and how deep.
std::string contacts_text(const TrackingContacts& c) {
  if (!c.any()) return "none";
  return c.first_pair + " at t = " + fixed(c.first_time, 3) + " s; " + std::to_string(c.ticks) +
         " ticks with a contact, deepest " + fixed(-c.deepest.distance * 1e3, 3) + " mm";
}

Json contacts_json(const TrackingContacts& c) {
  if (!c.any()) return Json{{"ticks", 0}};
  return Json{{"ticks", c.ticks},
              {"first_time", c.first_time},
              {"first_pair", c.first_pair},
              {"deepest_penetration", -c.deepest.distance}};
}

}  // namespace

void run_plan_scenario(const PlanCliOptions& given, const std::string& scene,
                       const std::string& controller_name, double settle_time,
                       double control_period, double max_acceleration, bool json) {
  std::vector<std::string> robots;
  for (const ShelfPickRobot& r : shelf_pick_robots()) robots.push_back(r.name);
  if (given.model.empty())
    throw UsageError("run plan needs a ROBOT (" + join(robots, " | ") +
                     "): mjarm run plan ROBOT --waypoints FILE");
  const ShelfPickRobot* robot = nullptr;
  try {
    robot = &shelf_pick_robot(given.model);
  } catch (const Error&) {
    throw UsageError("run plan: unknown robot '" + given.model + "'; robots: " + join(robots));
  }
  try {
    check_shelf_pick_controller(controller_name);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (!(settle_time >= 0.0)) throw UsageError("--settle-time must be >= 0");
  PlannedMotionWorld world = planned_motion_world(*robot, scene);
  PlanCliOptions options = given;
  options.model = robot->model;
  if (options.site.empty()) options.site = world.frame;
  const PlannedPath plan = plan_path(options, std::move(world.model));
  if (!plan.result.ok()) {
    if (json) {
      print_json(plan_json(plan));
    } else {
      print_plan(std::cout, plan);
    }
    throw Error("no plan: " + plan.result.message);
  }
  TrackingOptions tracking;
  tracking.controller = controller_name;
  tracking.settle_time = settle_time;
  tracking.control_period = control_period;
  tracking.max_acceleration = max_acceleration;
  const PlannedMotionRun tracked =
      track_planned_motion(*plan.chain, *robot, plan.start.qpos, plan.result.trajectory, tracking);
  const RunResult& run = tracked.run;
  const TrackingError& e = tracked.tracking;
  if (json) {
    Json doc = plan_json(plan);
    doc["scenario"] = "plan";
    doc["controller"] = controller_name;
    doc["run"] = Json{{"status", to_string(run.status)},
                      {"message", run.message},
                      {"end_time", run.end_time},
                      {"ticks", e.ticks},
                      {"max_position_error", e.max_position},
                      {"rms_position_error", e.rms_position},
                      {"final_position_error", e.final_position},
                      {"max_orientation_error", e.max_orientation},
                      {"final_orientation_error", e.final_orientation},
                      {"contacts", contacts_json(tracked.contacts)}};
    if (!scene.empty()) doc["scene"] = scene;
    print_json(doc);
  } else {
    print_plan(std::cout, plan);
    std::cout << "tracked in simulation by " << controller_name << " (torque mode, control period "
              << compact(tracked.control_period) << " s): " << to_string(run.status) << '\n';
    print_fields(
        std::cout,
        {{"position error [mm]", "max " + fixed(e.max_position * 1e3, 3) + ", RMS " +
                                     fixed(e.rms_position * 1e3, 3) + ", final " +
                                     fixed(e.final_position * 1e3, 3)},
         {"orientation error [mrad]", "max " + fixed(e.max_orientation * 1e3, 3) + ", final " +
                                          fixed(e.final_orientation * 1e3, 3)},
         {"simulated [s]", fixed(run.end_time, 3) + " (plan " +
                               fixed(plan.result.trajectory.duration(), 3) + " s + settle " +
                               compact(settle_time) + " s)"},
         {"contacts", contacts_text(tracked.contacts)}},
        2);
  }
  if (!run.ok())
    throw Error("the tracking run ended " + std::string(to_string(run.status)) + ": " +
                run.message);
  if (tracked.contacts.any())
    throw Error("the tracked robot touched " + contacts_text(tracked.contacts));
}

}  // namespace mjarm::cli
