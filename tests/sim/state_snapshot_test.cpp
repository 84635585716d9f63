#include "mjarm/sim/state_snapshot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"

namespace mjarm {
namespace {

// a box that falls onto a plane and slides (contacts, so the solver's warm start matters), an
// arm driven by a filtered actuator (activation state) and a mocap body
constexpr const char* kScene = R"(
<mujoco model="snapshot">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="box" pos="0 0 0.2">
      <freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="1"/>
    </body>
    <body name="arm" pos="1 0 0.5">
      <joint name="hinge" axis="0 1 0" damping="0.1"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02" mass="0.5"/>
    </body>
    <body name="target" mocap="true" pos="0.5 0.5 0.5"/>
  </worldbody>
  <actuator>
    <general name="filtered" joint="hinge" dyntype="filter" dynprm="0.05" gainprm="2"/>
  </actuator>
</mujoco>)";

/// qpos, qvel, act and time after each of @p steps steps, as bytes.
std::vector<mjtNum> trajectory(const mjModel& m, mjData& d, int steps) {
  std::vector<mjtNum> out;
  for (int i = 0; i < steps; ++i) {
    d.ctrl[0] = 0.5 * std::sin(0.01 * i);
    mj_step(&m, &d);
    out.push_back(d.time);
    out.insert(out.end(), d.qpos, d.qpos + m.nq);
    out.insert(out.end(), d.qvel, d.qvel + m.nv);
    out.insert(out.end(), d.act, d.act + m.na);
  }
  return out;
}

bool same_bits(const std::vector<mjtNum>& a, const std::vector<mjtNum>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(mjtNum)) == 0;
}

TEST(StateSnapshot, RestoringReplaysTheTrajectoryBitForBit) {
  const Robot robot = Robot::from_string(kScene);
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  d->xfrc_applied[6 * 1 + 0] = 0.3;  // a push on the box, part of the state
  trajectory(m, *d, 150);            // the box lands: contacts
  ASSERT_GT(d->ncon, 0);
  const StateSnapshot snapshot = StateSnapshot::of(m, *d);
  const std::vector<mjtNum> original = trajectory(m, *d, 300);

  snapshot.restore(m, *d);
  EXPECT_TRUE(same_bits(trajectory(m, *d, 300), original)) << "restore, then step";

  // into a fresh data, with mj_forward in between (a viewer's case): mj_forward writes no part
  // of the state, so the steps are the same
  DataPtr other = robot.make_data();
  snapshot.restore(m, *other);
  mj_forward(&m, other.get());
  EXPECT_TRUE(StateSnapshot::of(m, *other) == snapshot) << "mj_forward changed the state";
  EXPECT_DOUBLE_EQ(other->time, snapshot.time());
  EXPECT_TRUE(same_bits(trajectory(m, *other, 300), original)) << "restore, forward, step";
}

TEST(StateSnapshot, HoldsTheUserInputs) {
  const Robot robot = Robot::from_string(kScene);
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  d->ctrl[0] = 0.25;
  d->mocap_pos[0] = 0.9;
  d->qfrc_applied[0] = 1.5;
  const StateSnapshot snapshot = StateSnapshot::of(m, *d);
  DataPtr other = robot.make_data();
  snapshot.restore(m, *other);
  EXPECT_EQ(other->ctrl[0], 0.25);
  EXPECT_EQ(other->mocap_pos[0], 0.9);
  EXPECT_EQ(other->qfrc_applied[0], 1.5);
  EXPECT_TRUE(StateSnapshot::of(m, *other) == snapshot);
}

TEST(StateSnapshot, RefusesAnotherModelAndAnEmptySnapshot) {
  const Robot robot = Robot::from_string(kScene);
  const Robot panda = Robot::bundled("panda");
  DataPtr d = robot.make_data();
  DataPtr p = panda.make_data();
  const StateSnapshot snapshot = StateSnapshot::of(robot.model(), *d);
  try {
    snapshot.restore(panda.model(), *p);
    FAIL() << "restored into another model";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another model"), std::string::npos) << e.what();
  }
  EXPECT_THROW(StateSnapshot().restore(robot.model(), *d), Error);
}

TEST(StateSnapshot, ASimulationReplaysItsTicks) {
  // a torque-mode panda under a stateless PD: snapshot, tick, restore, tick again
  const Robot robot = Robot::bundled("panda_torque");
  SimulationOptions options;
  options.mode = SimulationMode::torque;
  Simulation sim(robot, options);
  sim.reset("home");
  const Chain chain(robot, "attachment_site");
  test::PdTorque pd(chain, 100.0, 20.0);
  sim.add_controller(pd);
  Reference reference;
  reference.joint.q = chain.gather(sim.data().qpos);
  reference.joint.q[0] += 0.3;
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(sim.tick(reference).ok());
  const StateSnapshot snapshot = sim.snapshot();
  const auto ticks = [&] {
    std::vector<mjtNum> qpos;
    for (int i = 0; i < 100; ++i) {
      EXPECT_TRUE(sim.tick(reference).ok());
      qpos.insert(qpos.end(), sim.data().qpos, sim.data().qpos + sim.model().nq);
    }
    return qpos;
  };
  const std::vector<mjtNum> first = ticks();
  sim.restore(snapshot);
  EXPECT_TRUE(same_bits(ticks(), first));
  const Robot other = Robot::from_string(kScene);
  EXPECT_THROW(sim.restore(StateSnapshot::of(other.model(), *other.make_data())), Error);
}

}  // namespace
}  // namespace mjarm
