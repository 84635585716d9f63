// Sanity of every bundled top-level model: it loads, its joints are limited and damped, it has its
// end-effector sites and a `home` key within limits, the position flavour holds home and stays
// stable around random configurations, the torque flavour falls, and the inertias are physical.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "model/mjcf_test_support.hpp"

#ifndef MJARM_MODELS_DIR
#define MJARM_MODELS_DIR "models"
#endif

namespace {

using mjarm::mjcf_test::DataPtr;
using mjarm::mjcf_test::ModelPtr;

/// One bundled robot: its position-servo file, its torque-motor file and its end-effector sites.
struct Bundle {
  std::string name;
  std::vector<std::string> sites;
  int dof;
};

void PrintTo(const Bundle& b, std::ostream* os) { *os << b.name; }

const std::vector<Bundle>& bundles() {
  static const std::vector<Bundle> kBundles = {
      {"planar2", {"tip"}, 2},
      {"arm6", {"grip"}, 8},
      {"panda", {"attachment_site"}, 7},
      {"panda_hand", {"attachment_site", "tcp"}, 9},
      {"iiwa14", {"attachment_site"}, 7},
      {"ur5e", {"attachment_site"}, 6},
      {"dual_arm", {"left_hand", "left_tcp", "right_hand", "right_tcp"}, 19},
  };
  return kBundles;
}

constexpr double kHoldTol = 0.05;  // rad or m, allowed drift from home under the servos
constexpr int kOneSecond = 500;    // steps of the 2 ms timestep

std::string path_of(const std::string& file) { return std::string(MJARM_MODELS_DIR) + "/" + file; }

ModelPtr load(const std::string& file, std::string* message = nullptr) {
  std::array<char, 1024> error{};
  const std::string path = path_of(file);
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  if (message != nullptr) *message = error.data();
  return m;
}

bool has_warnings(const mjData* d) {
  for (int i = 0; i < mjNWARNING; ++i) {
    if (d->warning[i].number > 0) return true;
  }
  return false;
}

int joint_of(const mjModel* m, int actuator) { return m->actuator_trnid[2 * actuator]; }

class BundledModels : public ::testing::TestWithParam<Bundle> {
 protected:
  void SetUp() override {
    const Bundle& b = GetParam();
    std::string msg;
    servo_ = load(b.name + ".xml", &msg);
    ASSERT_NE(servo_, nullptr) << b.name << ".xml: " << msg;
    EXPECT_EQ(msg, "") << b.name << ".xml loads with a warning";
    motor_ = load(b.name + "_torque.xml", &msg);
    ASSERT_NE(motor_, nullptr) << b.name << "_torque.xml: " << msg;
    EXPECT_EQ(msg, "") << b.name << "_torque.xml loads with a warning";
  }

  std::vector<const mjModel*> both() const { return {servo_.get(), motor_.get()}; }

  static int home(const mjModel* m) { return mj_name2id(m, mjOBJ_KEY, "home"); }

  ModelPtr servo_;
  ModelPtr motor_;
};

TEST_P(BundledModels, UsesTheCommonSimulationOptions) {
  for (const mjModel* m : both()) {
    EXPECT_EQ(m->opt.timestep, 0.002);
    EXPECT_EQ(m->opt.integrator, mjINT_EULER);
    EXPECT_EQ(m->opt.gravity[2], -9.81);
    // every scene has a floor plane and a light
    const int floor = mj_name2id(m, mjOBJ_GEOM, "floor");
    ASSERT_GE(floor, 0);
    EXPECT_EQ(m->geom_type[floor], mjGEOM_PLANE);
    EXPECT_GE(m->nlight, 1);
  }
}

TEST_P(BundledModels, EveryJointIsLimitedDampedAndHasArmature) {
  for (const mjModel* m : both()) {
    EXPECT_EQ(m->nv, GetParam().dof);
    EXPECT_EQ(m->njnt, m->nv) << "only hinge and slide joints expected";
    for (int j = 0; j < m->njnt; ++j) {
      const char* name = mj_id2name(m, mjOBJ_JOINT, j);
      ASSERT_NE(name, nullptr) << "joint " << j << " has no name";
      EXPECT_TRUE(m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE) << name;
      EXPECT_TRUE(m->jnt_limited[j]) << name;
      EXPECT_LT(m->jnt_range[2 * j], m->jnt_range[2 * j + 1]) << name;
      const int dof = m->jnt_dofadr[j];
      EXPECT_GT(m->dof_damping[dof], 0) << name;
      EXPECT_GT(m->dof_armature[dof], 0) << name;
    }
  }
}

TEST_P(BundledModels, HasTheEndEffectorSites) {
  for (const mjModel* m : both()) {
    for (const auto& site : GetParam().sites) {
      EXPECT_GE(mj_name2id(m, mjOBJ_SITE, site.c_str()), 0) << site;
    }
  }
}

TEST_P(BundledModels, BothFlavoursShareTheKinematicBody) {
  const mjModel* s = servo_.get();
  const mjModel* t = motor_.get();
  ASSERT_EQ(s->njnt, t->njnt);
  ASSERT_EQ(s->nbody, t->nbody);
  for (int j = 0; j < s->njnt; ++j) {
    EXPECT_STREQ(mj_id2name(s, mjOBJ_JOINT, j), mj_id2name(t, mjOBJ_JOINT, j));
    EXPECT_EQ(s->jnt_range[2 * j], t->jnt_range[2 * j]);
    EXPECT_EQ(s->jnt_range[2 * j + 1], t->jnt_range[2 * j + 1]);
  }
  for (int b = 0; b < s->nbody; ++b) {
    EXPECT_EQ(s->body_mass[b], t->body_mass[b]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s->body_pos[3 * b + k], t->body_pos[3 * b + k]);
  }
}

TEST_P(BundledModels, HomeKeyIsWithinLimitsAndFreeOfContacts) {
  for (const mjModel* m : both()) {
    const int key = home(m);
    ASSERT_GE(key, 0) << "no 'home' keyframe";
    for (int j = 0; j < m->njnt; ++j) {
      const double q = m->key_qpos[key * m->nq + m->jnt_qposadr[j]];
      EXPECT_GE(q, m->jnt_range[2 * j]) << mj_id2name(m, mjOBJ_JOINT, j);
      EXPECT_LE(q, m->jnt_range[2 * j + 1]) << mj_id2name(m, mjOBJ_JOINT, j);
    }
    DataPtr d(mj_makeData(m));
    mj_resetDataKeyframe(m, d.get(), key);
    mj_forward(m, d.get());
    EXPECT_EQ(d->ncon, 0) << "geoms touch at home";
  }
}

TEST_P(BundledModels, PositionFlavourHasOneServoPerJoint) {
  const mjModel* m = servo_.get();
  ASSERT_EQ(m->nu, m->njnt);
  std::vector<int> seen(m->njnt, 0);
  for (int a = 0; a < m->nu; ++a) {
    ASSERT_EQ(m->actuator_trntype[a], mjTRN_JOINT);
    const int j = joint_of(m, a);
    seen[j]++;
    const char* name = mj_id2name(m, mjOBJ_JOINT, j);
    EXPECT_STREQ(mj_id2name(m, mjOBJ_ACTUATOR, a), name);
    const mjtNum* gain = m->actuator_gainprm + a * mjNGAIN;
    const mjtNum* bias = m->actuator_biasprm + a * mjNBIAS;
    // force = kp ctrl - kp q - kv qdot
    EXPECT_EQ(m->actuator_dyntype[a], mjDYN_NONE) << name;
    EXPECT_EQ(m->actuator_gaintype[a], mjGAIN_FIXED) << name;
    EXPECT_EQ(m->actuator_biastype[a], mjBIAS_AFFINE) << name;
    EXPECT_GT(gain[0], 0) << name;
    EXPECT_EQ(bias[0], 0) << name;
    EXPECT_EQ(bias[1], -gain[0]) << name;
    EXPECT_LE(bias[2], 0) << name;
    EXPECT_EQ(m->actuator_gear[6 * a], 1) << name;
    EXPECT_TRUE(m->actuator_ctrllimited[a]) << name;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a], m->jnt_range[2 * j]) << name;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a + 1], m->jnt_range[2 * j + 1]) << name;
    EXPECT_TRUE(m->actuator_forcelimited[a]) << name;
    EXPECT_GT(m->actuator_forcerange[2 * a + 1], 0) << name;
    EXPECT_EQ(m->actuator_forcerange[2 * a], -m->actuator_forcerange[2 * a + 1]) << name;
    // the home key commands the home pose
    const int key = home(m);
    ASSERT_GE(key, 0);
    EXPECT_EQ(m->key_ctrl[key * m->nu + a], m->key_qpos[key * m->nq + m->jnt_qposadr[j]]) << name;
  }
  for (int j = 0; j < m->njnt; ++j) EXPECT_EQ(seen[j], 1) << mj_id2name(m, mjOBJ_JOINT, j);
}

TEST_P(BundledModels, TorqueFlavourHasOneMotorPerJointWithTheServosLimits) {
  const mjModel* m = motor_.get();
  const mjModel* s = servo_.get();
  ASSERT_EQ(m->nu, m->njnt);
  std::vector<int> seen(m->njnt, 0);
  for (int a = 0; a < m->nu; ++a) {
    ASSERT_EQ(m->actuator_trntype[a], mjTRN_JOINT);
    const int j = joint_of(m, a);
    seen[j]++;
    const char* name = mj_id2name(m, mjOBJ_JOINT, j);
    EXPECT_STREQ(mj_id2name(m, mjOBJ_ACTUATOR, a), name);
    EXPECT_EQ(m->actuator_gaintype[a], mjGAIN_FIXED) << name;
    EXPECT_EQ(m->actuator_gainprm[a * mjNGAIN], 1) << name;
    EXPECT_EQ(m->actuator_biastype[a], mjBIAS_NONE) << name;
    EXPECT_EQ(m->actuator_gear[6 * a], 1) << name;
    EXPECT_TRUE(m->actuator_ctrllimited[a]) << name;
    // the motor's ctrlrange is the servo's forcerange: the same published torque limit
    const int sa = mj_name2id(s, mjOBJ_ACTUATOR, name);
    ASSERT_GE(sa, 0) << name;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a], s->actuator_forcerange[2 * sa]) << name;
    EXPECT_EQ(m->actuator_ctrlrange[2 * a + 1], s->actuator_forcerange[2 * sa + 1]) << name;
    const int key = home(m);
    ASSERT_GE(key, 0);
    EXPECT_EQ(m->key_ctrl[key * m->nu + a], 0) << name;
  }
  for (int j = 0; j < m->njnt; ++j) EXPECT_EQ(seen[j], 1) << mj_id2name(m, mjOBJ_JOINT, j);
}

TEST_P(BundledModels, PositionServosHoldHomeForOneSecond) {
  const mjModel* m = servo_.get();
  DataPtr d(mj_makeData(m));
  const int key = home(m);
  ASSERT_GE(key, 0);
  mj_resetDataKeyframe(m, d.get(), key);
  const mjtNum* q_home = m->key_qpos + key * m->nq;
  for (int a = 0; a < m->nu; ++a) d->ctrl[a] = q_home[m->jnt_qposadr[joint_of(m, a)]];
  double drift = 0;
  for (int step = 0; step < kOneSecond; ++step) {
    mj_step(m, d.get());
    for (int i = 0; i < m->nq; ++i) drift = std::max(drift, std::abs(d->qpos[i] - q_home[i]));
  }
  EXPECT_FALSE(has_warnings(d.get()));
  EXPECT_LT(drift, kHoldTol);
  // gravity does load the servos, so the arm is not trivially at rest
  EXPECT_GT(drift, 0);
}

TEST_P(BundledModels, TorqueFlavourFallsWithZeroTorque) {
  const mjModel* m = motor_.get();
  DataPtr d(mj_makeData(m));
  const int key = home(m);
  ASSERT_GE(key, 0);
  mj_resetDataKeyframe(m, d.get(), key);
  for (int a = 0; a < m->nu; ++a) d->ctrl[a] = 0;
  const mjtNum* q_home = m->key_qpos + key * m->nq;
  for (int step = 0; step < kOneSecond; ++step) mj_step(m, d.get());
  double fall = 0;
  for (int i = 0; i < m->nq; ++i) {
    ASSERT_TRUE(std::isfinite(d->qpos[i]));
    fall = std::max(fall, std::abs(d->qpos[i] - q_home[i]));
  }
  EXPECT_GT(fall, 2 * kHoldTol);
}

TEST_P(BundledModels, ServosSettleNearRandomTargetsWithoutBlowingUp) {
  // contacts off: this checks the gains against the inertias (explicit Euler stability), not
  // whether a random pose happens to hit the floor
  const mjModel* src = servo_.get();
  ModelPtr m(mj_copyModel(nullptr, src));
  m->opt.disableflags |= mjDSBL_CONTACT;
  DataPtr d(mj_makeData(m.get()));
  std::mt19937_64 rng(20240611);
  for (int trial = 0; trial < 8; ++trial) {
    mj_resetData(m.get(), d.get());
    for (int a = 0; a < m->nu; ++a) {
      const int j = joint_of(m.get(), a);
      const double lo = m->jnt_range[2 * j], hi = m->jnt_range[2 * j + 1];
      const double margin = 0.1 * (hi - lo);
      std::uniform_real_distribution<double> start(lo + margin, hi - margin);
      const double q0 = start(rng);
      // a target up to 0.3 rad (or 10 % of the range for short joints) away, inside the range
      const double reach = std::min(0.3, margin);
      std::uniform_real_distribution<double> offset(-reach, reach);
      d->qpos[m->jnt_qposadr[j]] = q0;
      d->ctrl[a] = q0 + offset(rng);
    }
    double max_speed = 0;
    for (int step = 0; step < 3 * kOneSecond / 2; ++step) {
      mj_step(m.get(), d.get());
      for (int i = 0; i < m->nv; ++i) max_speed = std::max(max_speed, std::abs(d->qvel[i]));
    }
    ASSERT_FALSE(has_warnings(d.get())) << "trial " << trial;
    EXPECT_LT(max_speed, 20.0) << "trial " << trial;
    for (int a = 0; a < m->nu; ++a) {
      const int j = joint_of(m.get(), a);
      EXPECT_NEAR(d->qpos[m->jnt_qposadr[j]], d->ctrl[a], kHoldTol)
          << "trial " << trial << " joint " << mj_id2name(m.get(), mjOBJ_JOINT, j);
      EXPECT_LT(std::abs(d->qvel[m->jnt_dofadr[j]]), 0.05) << "trial " << trial;
    }
  }
}

TEST_P(BundledModels, InertialsArePhysical) {
  const mjModel* m = servo_.get();
  for (int b = 1; b < m->nbody; ++b) {
    const char* name = mj_id2name(m, mjOBJ_BODY, b);
    EXPECT_GT(m->body_mass[b], 0) << name;
    const mjtNum* i = m->body_inertia + 3 * b;
    for (int k = 0; k < 3; ++k) EXPECT_GT(i[k], 0) << name;
    // principal moments satisfy the triangle inequality
    const double tol = 1e-12 * (i[0] + i[1] + i[2]);
    EXPECT_GE(i[0] + i[1] + tol, i[2]) << name;
    EXPECT_GE(i[1] + i[2] + tol, i[0]) << name;
    EXPECT_GE(i[2] + i[0] + tol, i[1]) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(AllRobots, BundledModels, ::testing::ValuesIn(bundles()),
                         [](const ::testing::TestParamInfo<Bundle>& info) {
                           return info.param.name;
                         });

}  // namespace
