// The scenario registry (mjarm/scenarios/): names and lookup, the parameters as declared (names
// as command lines write them, kinds, ranges, defaults equal to the tasks' own), values checked
// with the scenario's name, and one trial of each scenario through the registry judged as the
// task judges it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/scenarios/docking_scenario.hpp"
#include "mjarm/scenarios/pick_place_scenario.hpp"
#include "mjarm/scenarios/plan_scenario.hpp"
#include "mjarm/scenarios/registry.hpp"
#include "mjarm/scenarios/shelf_pick_scenario.hpp"
#include "mjarm/scenarios/wiping_scenario.hpp"
#include "mjarm/teleop/bimanual_lift.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "mjarm/teleop/teleop_session.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

using Json = nlohmann::ordered_json;
using test::error_of;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

const FieldInfo& parameter(const Scenario& s, const std::string& name) {
  static std::vector<FieldInfo> table;
  table = s.parameters();
  for (const FieldInfo& p : table)
    if (p.path == name) return p;
  throw Error("no parameter " + name);
}

double metric(const Scenario& s, const TrialOutcome& o, const std::string& name) {
  for (std::size_t i = 0; i < s.metrics().size(); ++i)
    if (s.metrics()[i].name == name) return o.metrics.at(i);
  throw Error("no metric " + name);
}

TEST(Scenarios, AreListedAndFoundByName) {
  std::vector<std::string> names;
  for (const Scenario* s : scenarios()) names.emplace_back(s->name());
  EXPECT_THAT(
      names, ElementsAre("shelf-pick", "pick-place", "docking", "plan", "bimanual-lift", "wiping"));
  EXPECT_EQ(&find_scenario("docking"), scenarios()[2]);
  const std::string message = error_of([] { find_scenario("pick-plce"); });
  EXPECT_THAT(message, HasSubstr("unknown scenario 'pick-plce'; closest: pick-place"));
  for (const Scenario* s : scenarios()) {
    EXPECT_FALSE(s->doc().empty()) << s->name();
    EXPECT_FALSE(s->camera().empty()) << s->name();
    EXPECT_GE(s->verdicts().size(), 2u) << s->name();
    EXPECT_GE(s->metrics().size(), 4u) << s->name();
  }
}

TEST(Scenarios, ParametersAreTheDeclaredFieldsUnderTheirCommandLineNames) {
  const Scenario& pp = find_scenario("pick-place");
  const FieldInfo& size = parameter(pp, "object-size");
  EXPECT_EQ(size.kind, FieldKind::number);
  EXPECT_TRUE(size.optional);
  EXPECT_EQ(size.unit, "m");
  EXPECT_TRUE(size.value.is_null());  // drawn from the seed by default
  EXPECT_EQ(parameter(pp, "motion.approach-height").value, PickPlaceMotion{}.approach_height);
  EXPECT_EQ(parameter(pp, "motion.limits.max-velocity").unit, "m/s");
  EXPECT_THAT(parameter(pp, "grasp").names, ElementsAre("weld", "friction"));
  EXPECT_EQ(parameter(find_scenario("docking"), "controller.law").value, "se3");
  EXPECT_EQ(parameter(find_scenario("shelf-pick"), "pick").length, 3);

  const Json json = scenario_json(pp);
  EXPECT_EQ(json["name"], "pick-place");
  EXPECT_EQ(json["verdicts"][0], "placed");
  EXPECT_EQ(json["metrics"][1]["name"], "placement_error");
  EXPECT_EQ(json["metrics"][1]["better"], "lower");
}

TEST(Scenarios, DefaultsAreTheTasksOwn) {
  EXPECT_EQ(fields_to_json(pick_place_options(PickPlaceParameters{}).motion),
            fields_to_json(PickPlaceOptions{}.motion));
  EXPECT_EQ(fields_to_json(pick_place_options(PickPlaceParameters{}).criteria),
            fields_to_json(PickPlaceOptions{}.criteria));
  EXPECT_EQ(pick_place_options(PickPlaceParameters{}).grasp_force, PickPlaceOptions{}.grasp_force);
  EXPECT_EQ(fields_to_json(docking_options(DockingParameters{}).controller),
            fields_to_json(DockingOptions{}.controller));
  EXPECT_EQ(fields_to_json(docking_options(DockingParameters{}).motion),
            fields_to_json(DockingOptions{}.motion));
  const ShelfPickOptions shelf = shelf_pick_options(ShelfPickParameters{});
  EXPECT_EQ(shelf.request.robot, ShelfPickOptions{}.request.robot);
  EXPECT_EQ(shelf.settle_time, ShelfPickOptions{}.settle_time);
  EXPECT_EQ(fields_to_json(shelf.request.criteria),
            fields_to_json(ShelfPickOptions{}.request.criteria));
  EXPECT_EQ(shelf.gain_scale, ShelfPickOptions{}.gain_scale);
  EXPECT_EQ(fields_to_json(pick_place_options(PickPlaceParameters{}).ranges),
            fields_to_json(PickPlaceOptions{}.ranges));
  EXPECT_TRUE(same_geometry(docking_options(DockingParameters{}).geometry, DockingGeometry{}));
}

TEST(Scenarios, GainsRangesAndGeometryAreParametersThatReachTheTask) {
  // the shelf pick's gains: task-pd has no model feed-forward, so a quarter of its stiffness
  // (half its bandwidth) brings the tip in later and leaves it further off in the steady state
  const Scenario& shelf = find_scenario("shelf-pick");
  const Json base{{"robot", "planar2"}, {"controller", "task-pd"}, {"seed", 4}};
  Json soft = base;
  soft["gain-scale"] = 0.25;
  const TrialOutcome tuned = shelf.run(base);
  const TrialOutcome softer = shelf.run(soft);
  EXPECT_TRUE(tuned.success && softer.success) << softer.message;
  EXPECT_GT(metric(shelf, softer, "time_to_tolerance"), metric(shelf, tuned, "time_to_tolerance"));
  EXPECT_GT(metric(shelf, softer, "steady_state_max"),
            10.0 * metric(shelf, tuned, "steady_state_max"));
  EXPECT_EQ(softer.parameters["gain-scale"], 0.25);
  EXPECT_THAT(error_of([&] {
                shelf.resolve(Json{{"gain-scale", 0.0}});
              }),
              HasSubstr("shelf-pick: gain_scale must be in [0.01, 100], got 0"));
  // the pick and place's draw ranges
  const PickPlaceOptions heavy = pick_place_options(pick_place_scenario().parameters_from(
      Json{{"ranges.mass", {0.5, 0.5}}, {"ranges.friction", {0.8, 0.8}}, {"seed", 9}}));
  const PickPlaceTrial trial = draw_pick_place_trial(heavy);
  EXPECT_EQ(trial.object.mass, 0.5);
  EXPECT_EQ(trial.object.friction, 0.8);
  PickPlaceOptions reversed = heavy;
  reversed.ranges.mass = {0.5, 0.1};
  EXPECT_THAT(error_of([&] { draw_pick_place_trial(reversed); }),
              HasSubstr("the mass [kg] range must be finite, increasing"));
  // the docking's peg and socket: a scene built for other ones is refused before any work
  DockingOptions wide =
      docking_options(docking_scenario().parameters_from(Json{{"geometry.bore-radius", 0.016}}));
  EXPECT_EQ(wide.geometry.bore_radius, 0.016);
  wide.scene = std::make_shared<const DockingScene>(build_docking_scene());
  EXPECT_THAT(error_of([&] { run_docking(wide); }), HasSubstr("another peg or socket"));
}

TEST(Scenarios, ValuesAreCheckedWithTheScenariosName) {
  const Scenario& pp = find_scenario("pick-place");
  const Json values =
      pp.resolve(Json{{"object_size", 0.015}, {"grasp", "friction"}, {"motion.dwell-time", 0.2}});
  EXPECT_EQ(values["object-size"], 0.015);
  EXPECT_EQ(values["grasp"], "friction");
  EXPECT_EQ(values["motion.dwell-time"], 0.2);
  EXPECT_TRUE(values["target"].is_null());
  EXPECT_THAT(error_of([&] {
                pp.resolve(Json{{"objct-size", 0.02}});
              }),
              HasSubstr("pick-place: unknown parameter 'objct-size'; closest: object-size"));
  EXPECT_EQ(error_of([&] {
              pp.resolve(Json{{"object-size", 0.5}});
            }),
            "pick-place: object_size must be in [0.005, 0.05] [m], got 0.5");
  EXPECT_EQ(error_of([&] {
              pp.resolve(Json{{"seed", -1}});
            }),
            "pick-place: seed must be ≥ 0, got -1");
  EXPECT_THAT(error_of([&] {
                pp.resolve(Json{{"grasp", "glue"}});
              }),
              HasSubstr("unknown grasp 'glue'"));
  EXPECT_EQ(error_of([&] {
              pp.resolve(Json{{"target", {0.1}}});
            }),
            "pick-place: target must have 2 numbers, got 1");
  EXPECT_THAT(error_of([&] { pp.resolve(Json::array()); }),
              HasSubstr("pick-place: the parameters must be an object"));
  EXPECT_EQ(error_of([] {
              find_scenario("docking").resolve(Json{{"offset.dx", 0.06}});
            }),
            "docking: offset.dx must be in [-0.05, 0.05] [m], got 0.06");
}

TEST(Scenarios, AShelfPickThroughTheRegistryIsTheTasksOwnRun) {
  const Scenario& s = find_scenario("shelf-pick");
  const Json values{{"robot", "planar2"}, {"controller", "ct"}, {"seed", 4}};
  const TrialOutcome o = s.run(values);
  ShelfPickParameters p;
  p.robot = "planar2";
  p.controller = "ct";
  p.seed = 4;
  const ShelfPickReport direct = run_shelf_pick(shelf_pick_options(p));
  EXPECT_EQ(o.scenario, "shelf-pick");
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, "held");
  EXPECT_EQ(o.status, direct.run.status);
  ASSERT_EQ(o.metrics.size(), s.metrics().size());
  EXPECT_EQ(metric(s, o, "time_to_tolerance"), direct.metrics.time_to_tolerance);
  EXPECT_EQ(metric(s, o, "steady_state_max"), direct.metrics.steady_state_max);
  EXPECT_EQ(o.parameters["robot"], "planar2");
  EXPECT_EQ(o.parameters["criteria.tolerance"], PickCriteria{}.tolerance);

  const Json json = outcome_json(s, o);
  EXPECT_EQ(json["verdict"], "held");
  EXPECT_EQ(json["metrics"]["time_to_tolerance"], direct.metrics.time_to_tolerance);
  EXPECT_TRUE(json["outputs"]["recording"].is_null());
  EXPECT_EQ(json["parameters"]["seed"], 4);
}

TEST(Scenarios, APickAndPlaceThroughTheRegistryIsJudgedOnEveryCriterion) {
  const Scenario& s = find_scenario("pick-place");
  // a brisk machine: same states and checks as the classic pace
  const Json values{{"seed", 3},
                    {"motion.dwell-time", 0.15},
                    {"motion.grip-time", 0.3},
                    {"motion.release-time", 0.3},
                    {"motion.settle-time", 0.6},
                    {"motion.limits.max-velocity", 0.25},
                    {"motion.limits.max-acceleration", 2.0}};
  const TrialOutcome o = s.run(values);
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, "placed");
  EXPECT_LE(metric(s, o, "placement_error"), PickPlaceCriteria{}.placement_tolerance);
  EXPECT_GT(metric(s, o, "cycle_time"), 0.0);

  // a verdict other than success: a placement tolerance no trial meets
  Json strict = values;
  strict["criteria.placement-tolerance"] = 1e-7;
  const TrialOutcome missed = s.run(strict);
  EXPECT_FALSE(missed.success);
  EXPECT_EQ(missed.verdict, "misplaced");
  EXPECT_THAT(missed.message, HasSubstr("from the target"));
  EXPECT_EQ(metric(s, missed, "cycle_time"), metric(s, o, "cycle_time"));
}

TEST(Scenarios, ADockingThroughTheRegistrySeats) {
  const Scenario& s = find_scenario("docking");
  const Json values{{"offset.dx", 0.003},
                    {"motion.start-height", 0.03},
                    {"motion.approach-time", 0.6},
                    {"motion.insertion-speed", 0.02},
                    {"motion.hold-time", 1.2}};
  const TrialOutcome o = s.run(values);
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, "seated");
  EXPECT_LE(metric(s, o, "peak_force"), DockingCriteria{}.max_force);
  EXPECT_GT(metric(s, o, "first_contact_time"), 0.0);
}

TEST(Scenarios, AWipeThroughTheRegistryIsTheTasksOwnRun) {
  const Scenario& s = find_scenario("wiping");
  const Json values{
      {"control.law", "osc"}, {"path.length", 0.1}, {"motion.speed", 0.04}, {"seed", 2}};
  const TrialOutcome o = s.run(values);
  const WipingReport r = run_wiping(wiping_options(wiping_scenario().parameters_from(values)));
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, to_string(r.outcome));
  EXPECT_EQ(metric(s, o, "force_rms_error"), r.metrics.force_rms_error);
  EXPECT_EQ(metric(s, o, "path_max_error"), r.metrics.path_max_error);
  EXPECT_EQ(o.parameters["control.law"], "osc");
  EXPECT_EQ(o.parameters["motion.force"], WipingMotion{}.force);
}

TEST(Scenarios, ABimanualLiftThroughTheRegistryIsTheSessionsOwnLift) {
  const Scenario& s = find_scenario("bimanual-lift");
  const TrialOutcome o = s.run(Json::object());
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, "lifted");
  EXPECT_EQ(o.status, RunStatus::finished);
  // the same lift run by hand on a session of the same scene
  const Robot robot = Robot::bundled("dual_arm_box");
  TeleopSession session(robot, TeleopOptions{});
  SessionRecorder recorder(session);
  const BimanualLiftResult direct = run_bimanual_lift(recorder);
  EXPECT_EQ(metric(s, o, "lifted"), direct.lifted);
  EXPECT_EQ(metric(s, o, "sag"), direct.sag);
  EXPECT_EQ(o.end_time, session.stats().time);

  // a tolerance the lift cannot meet: judged not lifted, with the lift's own message
  const TrialOutcome strict = s.run(Json{{"lift.tolerance", 1e-6}});
  EXPECT_FALSE(strict.success);
  EXPECT_EQ(strict.verdict, "not_lifted");
  EXPECT_THAT(strict.message, HasSubstr("the bar rose"));
  EXPECT_EQ(metric(s, strict, "lifted"), direct.lifted);
}

TEST(Scenarios, APlannedMotionThroughTheRegistryIsTrackedOrNotPlanned) {
  const std::filesystem::path file = test::scratch() / "three.json";
  std::ofstream(file) << R"({"waypoints": [{"position": [0.45, 0.0, 0.50]},
    {"position": [0.45, 0.20, 0.40]}, {"position": [0.35, 0.25, 0.35]}]})";
  const Scenario& s = find_scenario("plan");
  const TrialOutcome o = s.run(Json{{"waypoints", file.string()}, {"controller", "ct"}});
  EXPECT_TRUE(o.success) << o.message;
  EXPECT_EQ(o.verdict, "tracked");
  PlannedMotionOptions options;
  options.waypoints = file;
  options.tracking.controller = "ct";
  const PlannedMotionReport direct = run_planned_motion(options);
  ASSERT_TRUE(direct.planned());
  EXPECT_EQ(metric(s, o, "max_position_error"), direct.tracked.tracking.max_position);
  EXPECT_EQ(metric(s, o, "duration"), direct.plan.result.trajectory.duration());
  EXPECT_LT(metric(s, o, "max_position_error"), 0.01);

  const std::filesystem::path far = test::scratch() / "far.json";
  std::ofstream(far) << R"({"waypoints": [{"position": [3.0, 0.0, 0.5]}]})";
  const TrialOutcome missed = s.run(Json{{"waypoints", far.string()}});
  EXPECT_FALSE(missed.success);
  EXPECT_EQ(missed.verdict, "not_planned");
  EXPECT_FALSE(missed.message.empty());
  EXPECT_THAT(error_of([&] { s.run(Json::object()); }), HasSubstr("waypoints names no file"));
}

}  // namespace
}  // namespace mjarm
