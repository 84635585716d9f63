// reset_data against mj_resetData: the same header and main buffer, byte for byte, after the
// data has been used (contacts, constraints, warnings), on every bundled model and on a model
// with a mocap body moved after the data was made.

#include "mjarm/sim/reset_data.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <random>
#include <string>

#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

// runs the model with random controls so every part of the buffer and header is non-zero
void stir(const mjModel& m, mjData& d, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int step = 0; step < 200; ++step) {
    for (int i = 0; i < m.nu; ++i) d.ctrl[i] = 5.0 * unit(random);
    for (int i = 0; i < m.nv; ++i) d.qfrc_applied[i] = unit(random);
    mj_step(&m, &d);
  }
  d.warning[mjWARN_BADQACC].number = 3;
  d.time = 12.5;
}

::testing::AssertionResult same_reset(const mjModel& m, std::uint64_t seed) {
  DataPtr ours(mj_makeData(&m));
  DataPtr theirs(mj_makeData(&m));
  stir(m, *ours, seed);
  stir(m, *theirs, seed);
  reset_data(m, *ours);
  mj_resetData(&m, theirs.get());
  const std::size_t begin = offsetof(mjData, pstack);
  const std::size_t end = offsetof(mjData, buffer);
  if (std::memcmp(reinterpret_cast<const char*>(ours.get()) + begin,
                  reinterpret_cast<const char*>(theirs.get()) + begin, end - begin) != 0)
    return ::testing::AssertionFailure() << "the info headers differ";
  const auto* a = static_cast<const unsigned char*>(ours->buffer);
  const auto* b = static_cast<const unsigned char*>(theirs->buffer);
  for (int i = 0; i < m.nbuffer; ++i) {
    if (a[i] != b[i]) return ::testing::AssertionFailure() << "the buffers differ at byte " << i;
  }
  return ::testing::AssertionSuccess();
}

TEST(ResetData, EveryBundledModelResetsLikeMujoco) {
  for (const std::string& name : Robot::bundled_names()) {
    const Robot robot = Robot::bundled(name);
    EXPECT_TRUE(same_reset(robot.model(), 7)) << name;
  }
}

TEST(ResetData, AMocapBodyReturnsToItsModelPoseAfterTheModelChanged) {
  const Robot robot = Robot::from_string(R"(
<mujoco>
  <worldbody>
    <body name="target" mocap="true" pos="0.1 0.2 0.3" quat="0 1 0 0">
      <geom type="sphere" size="0.01" contype="0" conaffinity="0"/>
    </body>
    <body name="ball" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.05"/>
    </body>
    <geom type="plane" size="1 1 0.1"/>
  </worldbody>
</mujoco>)");
  mjModel* m = mj_copyModel(nullptr, &robot.model());
  ASSERT_NE(m, nullptr);
  m->body_pos[3 * 1 + 2] = 0.7;  // the mocap body moved in the model (a randomized scene)
  m->qpos0[2] = 2.0;             // and the ball's default height
  EXPECT_TRUE(same_reset(*m, 11));
  DataPtr d(mj_makeData(m));
  d->mocap_pos[2] = -1.0;
  reset_data(*m, *d);
  EXPECT_EQ(d->mocap_pos[2], 0.7);
  EXPECT_EQ(d->qpos[2], 2.0);
  mj_deleteModel(m);
}

}  // namespace
}  // namespace mjarm
