// ObservationSet: names to arrays, each value checked against a second way of computing it;
// unknown, unavailable and switched-off observations are errors that say which.

#include "mjarm/env/observation_set.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "env/env_test_support.hpp"
#include "mjarm/env/environment.hpp"
#include "mjarm/lie/rotation.hpp"

namespace mjarm {
namespace {

using test::expect_error_containing;
using test::reach_task;

EnvironmentOptions with_observations(std::vector<std::string> names,
                                     ActionSpace space = ActionSpace::ee_pose_deltas) {
  EnvironmentOptions o;
  o.observations = std::move(names);
  o.action_space = space;
  return o;
}

TEST(ObservationSet, ValuesMatchMujocoAfterAForwardPass) {
  Environment env(reach_task(), with_observations({"joint_positions", "joint_velocities", "ee_pose",
                                                   "ee_twist", "sensor:arm/ft_force"}));
  env.reset(4);
  const std::vector<double> action{0.01, -0.01, 0.005, 0.05, 0.0, -0.05};
  TimeStep ts;
  for (int k = 0; k < 5; ++k) ts = env.step(action);
  const Observation& o = ts.observation;
  const Chain& chain = env.task().chain();
  const Simulation& sim = env.simulation();
  const mjModel& m = sim.model();
  // MuJoCo's own kinematics of the current state, on a scratch copy
  DataPtr d = env.task().robot().make_data();
  std::copy(sim.data().qpos, sim.data().qpos + m.nq, d->qpos);
  std::copy(sim.data().qvel, sim.data().qvel + m.nv, d->qvel);
  mj_forward(&m, d.get());
  for (int i = 0; i < chain.size(); ++i) {
    EXPECT_EQ(o["joint_positions"][i], d->qpos[chain.qpos_address(i)]);
    EXPECT_EQ(o["joint_velocities"][i], d->qvel[chain.dof_address(i)]);
  }
  const int site = chain.frame().id;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(o["ee_pose"][k], d->site_xpos[3 * site + k], 1e-12);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = d->site_xmat[9 * site + 3 * r + c];
  const Eigen::Vector4d q(o["ee_pose"][3], o["ee_pose"][4], o["ee_pose"][5], o["ee_pose"][6]);
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_LT((rotation_from_quaternion(q) - R).norm(), 1e-12);
  // twist: MuJoCo's site velocity (mj_objectVelocity gives [ω; v], world axes with flg_local 0)
  mjtNum velocity[6];
  mj_objectVelocity(&m, d.get(), mjOBJ_SITE, site, velocity, 0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(o["ee_twist"][k], velocity[3 + k], 1e-10);
    EXPECT_NEAR(o["ee_twist"][3 + k], velocity[k], 1e-10);
  }
  // the sensor is MuJoCo's sensordata as the step left it
  const std::span<const double> force = sim.sensor("arm/ft_force");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(o["sensor:arm/ft_force"][k], force[k]);
  EXPECT_GT(std::abs(force[2]), 0.1);  // the F/T site carries the flange's weight
}

TEST(ObservationSet, SpecsHaveTheDocumentedShapesAndBounds) {
  Environment env(reach_task(),
                  with_observations({"ee_pose", "target", "joint_positions", "contact_forces"}));
  const ObservationSpec& spec = env.observation_spec();
  EXPECT_EQ(spec.names(),
            (std::vector<std::string>{"ee_pose", "target", "joint_positions", "contact_forces"}));
  EXPECT_EQ(spec.at("ee_pose").size(), 7);
  EXPECT_EQ(spec.at("ee_pose").minimum[3], -1.0);
  EXPECT_EQ(spec.at("contact_forces").size(), 3);
  // MuJoCo's joint limits are soft: the spec does not claim them (test below)
  EXPECT_TRUE(spec.at("joint_positions").minimum.array().isInf().all());
  EXPECT_TRUE(spec.at("joint_positions").maximum.array().isInf().all());
  const auto& reach = static_cast<const ReachTask&>(env.task());
  EXPECT_EQ(spec.at("target").maximum,
            reach.options().target_center + reach.options().target_half_width);
  // every value of an observation lies within its bounds (the target drawn inside its box)
  const TimeStep ts = env.reset(8);
  for (int a = 0; a < spec.count(); ++a) {
    const std::span<const double> v = ts.observation.at(a);
    for (std::size_t i = 0; i < v.size(); ++i) {
      EXPECT_GE(v[i], spec.arrays()[a].minimum[static_cast<Eigen::Index>(i)]);
      EXPECT_LE(v[i], spec.arrays()[a].maximum[static_cast<Eigen::Index>(i)]);
    }
  }
}

TEST(ObservationSet, JointPositionsPastASoftLimitStayWithinTheirSpec) {
  // full negative torques drive a joint past its limit (MuJoCo's limits are soft): the value is
  // returned as it is, and the spec (found by dm_env's conformance test) still holds it
  Environment env(reach_task(), with_observations({"joint_positions"}, ActionSpace::joint_torques));
  const ArraySpec& spec = env.observation_spec().at("joint_positions");
  const Eigen::VectorXd action = env.action_spec().minimum;
  const std::vector<double> push(action.data(), action.data() + action.size());
  const Chain& chain = env.task().chain();
  TimeStep ts = env.reset(1);
  bool beyond = false;
  for (int k = 0; k < 50 && !beyond && !ts.last(); ++k) {
    ts = env.step(push);
    const std::span<const double> q = ts.observation["joint_positions"];
    for (int i = 0; i < chain.size(); ++i) {
      beyond = beyond || q[i] < chain.lower()[i] || q[i] > chain.upper()[i];
      EXPECT_GE(q[i], spec.minimum[i]);
      EXPECT_LE(q[i], spec.maximum[i]);
    }
  }
  EXPECT_TRUE(beyond);
}

TEST(ObservationSet, ContactForcesPushTheArmOffTheFloor) {
  // unactuated, the arm folds down onto the floor: the floor pushes up on it
  Environment env(reach_task(), with_observations({"contact_forces"}, ActionSpace::joint_torques));
  TimeStep ts = env.reset(1);
  EXPECT_EQ(ts.observation["contact_forces"][2], 0.0);  // free at the start
  const std::vector<double> limp(7, 0.0);
  for (int k = 0; k < 100; ++k) ts = env.step(limp);
  const std::span<const double> f = ts.observation["contact_forces"];
  EXPECT_GT(f[2], 1.0);
  EXPECT_LT(f[2], 18.0 * 9.81);  // never more than the whole arm's weight (≈ 18 kg)
  EXPECT_GT(env.simulation().contacts(0).contacts, 0);
}

TEST(ObservationSet, UnknownNamesAreErrorsListingTheAvailableOnes) {
  expect_error_containing(
      [] { Environment env(reach_task(), with_observations({"joint_positons"})); },
      {"unknown observation 'joint_positons'", "task 'reach'", "closest: joint_positions",
       "available:", "ee_twist", "target_offset", "sensor:arm/ft_force"});
  expect_error_containing(
      [] {
        Environment env(reach_task(), with_observations({"ee_pose", "ee_pose"}));
      },
      {"'ee_pose' is listed twice"});
}

TEST(ObservationSet, RequestedButSwitchedOffIsAnError) {
  // the reach task has no object: object_pose is switched off there, not silently empty
  expect_error_containing(
      [] {
        Environment env(reach_task(), with_observations({"ee_pose", "object_pose"}));
      },
      {"observation 'object_pose' is switched off in task 'reach'", "target, target_offset"});
  // a task that provides it
  Environment hooks(std::make_unique<test::HookTask>(),
                    with_observations({"object_pose"}, ActionSpace::joint_torques));
  const TimeStep ts = hooks.reset(1);
  EXPECT_EQ(ts.observation["object_pose"][0], 0.5);  // the box's start in the model
}

TEST(ObservationSet, SensorsByNameAndTheirErrors) {
  Environment hooks(
      std::make_unique<test::HookTask>(),
      with_observations({"sensor:j1_pos", "sensor:never"}, ActionSpace::joint_torques));
  EXPECT_EQ(hooks.observation_spec().at("sensor:never").minimum[0], 0.0);  // touch: positive
  hooks.reset(1);
  const TimeStep ts = hooks.step(std::vector<double>{5.0, 0.0});
  EXPECT_EQ(ts.observation["sensor:j1_pos"][0], hooks.simulation().sensor("j1_pos")[0]);
  EXPECT_NE(ts.observation["sensor:j1_pos"][0], 0.0);
  expect_error_containing(
      [] {
        Environment env(std::make_unique<test::HookTask>(), with_observations({"sensor:j2_pos"}));
      },
      {"observation 'sensor:j2_pos'", "no sensor 'j2_pos'", "sensor:j1_pos, sensor:never"});
}

TEST(ObservationSet, ContactForcesOnAModelWithoutContactsIsSwitchedOff) {
  // the same two-joint arm with contacts disabled
  std::string xml = test::kHookArm;
  const std::string option = "<option timestep=\"0.002\"/>";
  xml.replace(xml.find(option), option.size(),
              "<option timestep=\"0.002\"><flag contact=\"disable\"/></option>");
  class NoContactTask final : public EnvTask {
   public:
    explicit NoContactTask(const std::string& xml)
        : robot_(Robot::from_string(xml)), chain_(robot_, "tip") {}
    std::unique_ptr<EnvTask> clone() const override {
      return std::make_unique<NoContactTask>(*this);
    }
    std::string_view name() const noexcept override { return "no-contact"; }
    std::string_view description() const noexcept override { return ""; }
    const Robot& robot() const noexcept override { return robot_; }
    const Chain& chain() const noexcept override { return chain_; }
    void initialize_episode(Simulation& sim, EpisodeRandom&) override { sim.reset(); }
    double reward(const StepContext&) const noexcept override { return 0.0; }

   private:
    Robot robot_;
    Chain chain_;
  };
  expect_error_containing(
      [&] {
        Environment env(std::make_unique<NoContactTask>(xml),
                        with_observations({"contact_forces"}, ActionSpace::joint_torques));
      },
      {"'contact_forces' is switched off in task 'no-contact'", "disables contacts"});
  const std::unique_ptr<EnvTask> reach = reach_task();
  Simulation sim(reach->robot());
  expect_error_containing([&] { ObservationSet empty(*reach, sim, {}); }, {"none requested"});
}

}  // namespace
}  // namespace mjarm
