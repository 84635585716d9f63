// The contact and actuator-range additions of the recorder (what `mjarm plot` draws).

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "mjarm/sim/recorder.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm {
namespace {

// A 2 kg box dropped 1 cm onto the floor: once it rests, the contacts carry its weight.
constexpr const char* kDroppedBox = R"(
<mujoco model="box_on_floor">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="box" pos="0 0 0.11">
      <freejoint name="box"/>
      <geom name="box" type="box" size="0.1 0.1 0.1" mass="2"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(RecorderContacts, TheRestingBoxWeighsItsMassTimesG) {
  const Robot robot = Robot::from_string(kDroppedBox);
  Simulation sim(robot, SimulationOptions{});
  test::TempDir dir("contacts");
  Recorder recorder(sim, dir.path());
  ConstantReferenceSource source(Reference{});
  const RunResult run = sim.run(source, 1.0, &recorder);
  recorder.finalize(run);

  const test::Csv state = test::read_csv(dir.path() / "state.csv");
  ASSERT_GE(state.column("contact.count"), 0);
  ASSERT_GE(state.column("contact.normal_force"), 0);
  // falling: no contact, no force
  EXPECT_EQ(state.value(0, "contact.count"), 0.0);
  EXPECT_EQ(state.value(0, "contact.normal_force"), 0.0);
  // resting on four corners (MuJoCo's box-plane collision): the normal forces sum to m·g
  const std::size_t last = state.rows.size() - 1;
  EXPECT_GE(state.value(last, "contact.count"), 1.0);
  const double weight = 2.0 * 9.81;
  EXPECT_NEAR(state.value(last, "contact.normal_force"), weight, 0.01 * weight);
}

TEST(RecorderContacts, TheSummaryListsTheForceRangeOfEachActuator) {
  const Robot robot = Robot::bundled("planar2_torque");
  Simulation sim(robot, SimulationOptions{});
  test::TempDir dir("actuators");
  Recorder recorder(sim, dir.path());
  recorder.finalize("finished");
  const nlohmann::json s = nlohmann::json::parse(test::read_text(dir.path() / "summary.json"));
  ASSERT_EQ(s["actuators"].size(), 2u);
  // motors with gear 1 and ctrlrange ±20 and ±10 N m (models/planar2_torque.xml)
  EXPECT_EQ(s["actuators"][0]["name"], "shoulder");
  EXPECT_EQ(s["actuators"][0]["kind"], "motor");
  EXPECT_EQ(s["actuators"][0]["joint"], "shoulder");
  EXPECT_EQ(s["actuators"][0]["gear"], 1.0);
  EXPECT_EQ(s["actuators"][0]["force_range"][0], -20.0);
  EXPECT_EQ(s["actuators"][0]["force_range"][1], 20.0);
  EXPECT_EQ(s["actuators"][1]["force_range"][1], 10.0);
}

TEST(RecorderContacts, KinematicModeHasNoContactForces) {
  const Robot robot = Robot::from_string(kDroppedBox);
  SimulationOptions options;
  options.mode = SimulationMode::kinematic;
  Simulation sim(robot, options);
  test::TempDir dir("kinematic");
  Recorder recorder(sim, dir.path());
  // the box pressed 1 cm into the floor: contacts, but no constraint forces to report
  const double qpos[7] = {0.0, 0.0, 0.09, 1.0, 0.0, 0.0, 0.0};
  sim.move(qpos, 0.002, &recorder);
  recorder.finalize("finished");
  const test::Csv state = test::read_csv(dir.path() / "state.csv");
  ASSERT_EQ(state.rows.size(), 1u);
  EXPECT_GE(state.value(0, "contact.count"), 1.0);
  EXPECT_TRUE(std::isnan(state.value(0, "contact.normal_force")));
  EXPECT_GE(state.column("contact.normal_force"), 0);
}

}  // namespace
}  // namespace mjarm
