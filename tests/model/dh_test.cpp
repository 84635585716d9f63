// Cross-checks the bundled arm models against an independent Denavit-Hartenberg forward kinematics
// written here from the published tables: the end-effector site pose reported by MuJoCo must equal
// the DH product to machine precision at random joint configurations within the limits.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <iomanip>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "model/mjcf_test_support.hpp"

#ifndef MJARM_MODELS_DIR
#define MJARM_MODELS_DIR "models"
#endif

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kPosTol = 1e-9;  // m
constexpr double kRotTol = 1e-9;  // rad
constexpr int kSamples = 1000;

using Mat4 = Eigen::Matrix4d;
using Mat3 = Eigen::Matrix3d;

using mjarm::mjcf_test::DataPtr;
using mjarm::mjcf_test::ModelPtr;

// models/<file>, failing the test when MuJoCo rejects it
ModelPtr load_model_file(const std::string& file) {
  const std::string path = std::string(MJARM_MODELS_DIR) + "/" + file;
  std::array<char, 1024> error{};
  ModelPtr m(mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  EXPECT_NE(m, nullptr) << path << ": " << error.data();
  return m;
}

// elementary homogeneous transforms
Mat4 rot_x(double a) {
  Mat4 t = Mat4::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return t;
}
Mat4 rot_z(double a) {
  Mat4 t = Mat4::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}
Mat4 trans(double x, double y, double z) {
  Mat4 t = Mat4::Identity();
  t.block<3, 1>(0, 3) = Eigen::Vector3d(x, y, z);
  return t;
}

enum class Convention { kModified, kStandard };

/// One DH row. Modified (Craig): T = Rx(alpha) Tx(a) Rz(theta) Tz(d) with alpha, a the "previous"
/// link's values as Franka tabulates them. Standard: A = Rz(theta) Tz(d) Tx(a) Rx(alpha).
struct DhRow {
  double a;
  double d;
  double alpha;
};

struct DhArm {
  Convention convention;
  std::vector<DhRow> rows;
  Mat4 tool;  // constant transform after the last row (e.g. the Panda flange)
};

Mat4 dh_fk(const DhArm& arm, const std::vector<double>& q) {
  Mat4 t = Mat4::Identity();
  for (size_t i = 0; i < arm.rows.size(); ++i) {
    const DhRow& r = arm.rows[i];
    if (arm.convention == Convention::kModified) {
      t = t * rot_x(r.alpha) * trans(r.a, 0, 0) * rot_z(q[i]) * trans(0, 0, r.d);
    } else {
      t = t * rot_z(q[i]) * trans(0, 0, r.d) * trans(r.a, 0, 0) * rot_x(r.alpha);
    }
  }
  return t * arm.tool;
}

// published tables
DhArm panda_dh() {
  return {Convention::kModified,
          {{0, 0.333, 0},
           {0, 0, -kPi / 2},
           {0, 0.316, kPi / 2},
           {0.0825, 0, kPi / 2},
           {-0.0825, 0.384, -kPi / 2},
           {0, 0, kPi / 2},
           {0.088, 0, kPi / 2}},
          trans(0, 0, 0.107)};
}

DhArm iiwa14_dh() {
  return {Convention::kStandard,
          {{0, 0.36, -kPi / 2},
           {0, 0, kPi / 2},
           {0, 0.42, kPi / 2},
           {0, 0, -kPi / 2},
           {0, 0.4, -kPi / 2},
           {0, 0, kPi / 2},
           {0, 0.126, 0}},
          Mat4::Identity()};
}

DhArm ur5e_dh() {
  return {Convention::kStandard,
          {{0, 0.1625, kPi / 2},
           {-0.425, 0, 0},
           {-0.3922, 0, 0},
           {0, 0.1333, kPi / 2},
           {0, 0.0997, -kPi / 2},
           {0, 0.0996, 0}},
          Mat4::Identity()};
}

std::vector<std::string> names(const std::string& prefix, int n) {
  std::vector<std::string> out;
  for (int i = 1; i <= n; ++i) out.push_back(prefix + "joint" + std::to_string(i));
  return out;
}

/// Pose of a body or site from mjData as a 4x4 transform.
Mat4 pose(const mjtNum* pos, const mjtNum* mat) {
  Mat4 t = Mat4::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t(r, c) = mat[3 * r + c];
    t(r, 3) = pos[r];
  }
  return t;
}

/// Rotation angle of R_a^T R_b, robust for tiny angles (quaternion, atan2).
double angle_between(const Mat3& r_a, const Mat3& r_b) {
  const Eigen::Quaterniond dq(Mat3(r_a.transpose() * r_b));
  return 2.0 * std::atan2(dq.vec().norm(), std::abs(dq.w()));
}

struct SiteCheck {
  std::string site;
  Mat4 extra;  // site pose = DH(q) * extra
};

/// Samples kSamples random configurations of `joints` (and of every other joint of the model)
/// within the model's limits and compares each site with base_body_pose * DH(q) * extra.
void check_arm(const std::string& file, const std::string& base_body,
               const std::vector<std::string>& joints, const DhArm& arm,
               const std::vector<SiteCheck>& sites, unsigned seed) {
  ModelPtr m = load_model_file(file);
  ASSERT_NE(m, nullptr);
  DataPtr d(mj_makeData(m.get()));
  const int base = mj_name2id(m.get(), mjOBJ_BODY, base_body.c_str());
  ASSERT_GE(base, 0) << base_body;
  std::vector<int> adr;
  for (const auto& j : joints) {
    const int id = mj_name2id(m.get(), mjOBJ_JOINT, j.c_str());
    ASSERT_GE(id, 0) << file << ": joint " << j;
    ASSERT_EQ(m->jnt_type[id], mjJNT_HINGE);
    adr.push_back(m->jnt_qposadr[id]);
  }
  std::vector<int> site_ids;
  for (const auto& s : sites) {
    const int id = mj_name2id(m.get(), mjOBJ_SITE, s.site.c_str());
    ASSERT_GE(id, 0) << file << ": site " << s.site;
    site_ids.push_back(id);
  }

  std::mt19937_64 rng(seed);
  std::vector<double> q(joints.size());
  double worst_pos = 0, worst_rot = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    // every joint of the model gets a random value (lift, fingers too), the arm's are recorded
    for (int j = 0; j < m->njnt; ++j) {
      std::uniform_real_distribution<double> u(m->jnt_range[2 * j], m->jnt_range[2 * j + 1]);
      d->qpos[m->jnt_qposadr[j]] = u(rng);
    }
    for (size_t i = 0; i < adr.size(); ++i) q[i] = d->qpos[adr[i]];
    mj_kinematics(m.get(), d.get());

    const Mat4 x_wb = pose(d->xpos + 3 * base, d->xmat + 9 * base);
    const Mat4 x_b_dh = dh_fk(arm, q);
    for (size_t k = 0; k < sites.size(); ++k) {
      const Mat4 expected = x_wb * x_b_dh * sites[k].extra;
      const Mat4 actual = pose(d->site_xpos + 3 * site_ids[k], d->site_xmat + 9 * site_ids[k]);
      const double pos_err = (expected.block<3, 1>(0, 3) - actual.block<3, 1>(0, 3)).norm();
      const double rot_err = angle_between(expected.block<3, 3>(0, 0), actual.block<3, 3>(0, 0));
      worst_pos = std::max(worst_pos, pos_err);
      worst_rot = std::max(worst_rot, rot_err);
      ASSERT_LT(pos_err, kPosTol) << file << " site " << sites[k].site << " sample " << sample;
      ASSERT_LT(rot_err, kRotTol) << file << " site " << sites[k].site << " sample " << sample;
    }
  }
  std::ostringstream worst;
  worst << std::scientific << std::setprecision(2) << worst_pos << " m, " << worst_rot << " rad";
  ::testing::Test::RecordProperty("worst_error_" + file, worst.str());
}

const std::vector<SiteCheck> kFlangeOnly = {{"attachment_site", Mat4::Identity()}};

TEST(BundledModelDh, DhImplementationReproducesDatasheetZeroPoses) {
  // zero-configuration flange positions computed by hand from the datasheets' link lengths,
  // so a sign slip shared by the DH code and the MJCF cannot pass unnoticed.
  const Mat4 panda0 = dh_fk(panda_dh(), std::vector<double>(7, 0.0));
  EXPECT_NEAR((panda0.block<3, 1>(0, 3) - Eigen::Vector3d(0.088, 0, 0.926)).norm(), 0, 1e-12);
  EXPECT_NEAR((panda0.block<3, 1>(0, 2) - Eigen::Vector3d(0, 0, -1)).norm(), 0, 1e-12);

  const Mat4 iiwa0 = dh_fk(iiwa14_dh(), std::vector<double>(7, 0.0));
  EXPECT_NEAR((iiwa0.block<3, 1>(0, 3) - Eigen::Vector3d(0, 0, 1.306)).norm(), 0, 1e-12);
  EXPECT_NEAR((iiwa0.block<3, 1>(0, 2) - Eigen::Vector3d(0, 0, 1)).norm(), 0, 1e-12);

  // ur5e stretched out along -x: tool at (-(0.425 + 0.3922), -(0.1333 + 0.0996), 0.1625 - 0.0997)
  const Mat4 ur0 = dh_fk(ur5e_dh(), std::vector<double>(6, 0.0));
  EXPECT_NEAR((ur0.block<3, 1>(0, 3) - Eigen::Vector3d(-0.8172, -0.2329, 0.0628)).norm(), 0, 1e-12);
  EXPECT_NEAR((ur0.block<3, 1>(0, 2) - Eigen::Vector3d(0, -1, 0)).norm(), 0, 1e-12);
}

TEST(BundledModelDh, PandaFlangeMatchesModifiedDh) {
  check_arm("panda.xml", "link0", names("", 7), panda_dh(), kFlangeOnly, 1);
  check_arm("panda_torque.xml", "link0", names("", 7), panda_dh(), kFlangeOnly, 2);
}

TEST(BundledModelDh, PandaHandFlangeAndTcpMatchModifiedDh) {
  // Franka Hand: rotated -pi/4 about the flange z axis, tcp 0.1034 m further along z
  const std::vector<SiteCheck> sites = {{"attachment_site", Mat4::Identity()},
                                        {"tcp", rot_z(-kPi / 4) * trans(0, 0, 0.1034)}};
  check_arm("panda_hand.xml", "link0", names("", 7), panda_dh(), sites, 3);
}

TEST(BundledModelDh, Iiwa14FlangeMatchesStandardDh) {
  check_arm("iiwa14.xml", "link0", names("", 7), iiwa14_dh(), kFlangeOnly, 4);
  check_arm("iiwa14_torque.xml", "link0", names("", 7), iiwa14_dh(), kFlangeOnly, 5);
}

TEST(BundledModelDh, Ur5eFlangeMatchesStandardDh) {
  const std::vector<std::string> joints = {"shoulder_pan", "shoulder_lift", "elbow",
                                           "wrist_1",      "wrist_2",       "wrist_3"};
  check_arm("ur5e.xml", "base", joints, ur5e_dh(), kFlangeOnly, 6);
  check_arm("ur5e_torque.xml", "base", joints, ur5e_dh(), kFlangeOnly, 7);
}

TEST(BundledModelDh, DualArmHandsMatchPandaDhFromTheirBases) {
  check_arm("dual_arm.xml", "left_link0", names("left_", 7), panda_dh(),
            {{"left_hand", Mat4::Identity()}}, 8);
  check_arm("dual_arm.xml", "right_link0", names("right_", 7), panda_dh(),
            {{"right_hand", Mat4::Identity()}}, 9);
}

TEST(BundledModelDh, SingleArmBasesSitAtTheWorldOrigin) {
  // the DH base frame is the model's world frame for the single-arm scenes
  for (const auto& [file, body] : std::vector<std::pair<std::string, std::string>>{
           {"panda.xml", "link0"}, {"iiwa14.xml", "link0"}, {"ur5e.xml", "base"}}) {
    ModelPtr m = load_model_file(file);
    ASSERT_NE(m, nullptr);
    DataPtr d(mj_makeData(m.get()));
    mj_kinematics(m.get(), d.get());
    const int b = mj_name2id(m.get(), mjOBJ_BODY, body.c_str());
    ASSERT_GE(b, 0);
    const Mat4 x = pose(d->xpos + 3 * b, d->xmat + 9 * b);
    EXPECT_LT((x - Mat4::Identity()).cwiseAbs().maxCoeff(), 1e-15) << file;
  }
}

struct Published {
  std::string file;
  std::vector<std::string> joints;
  std::vector<double> lo, hi, torque;
};

TEST(BundledModelDh, JointAndTorqueLimitsAreThePublishedOnes) {
  const double deg = kPi / 180;
  const std::vector<Published> robots = {
      {"panda",
       names("", 7),
       {-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973},
       {2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973},
       {87, 87, 87, 87, 12, 12, 12}},
      {"iiwa14",
       names("", 7),
       {-170 * deg, -120 * deg, -170 * deg, -120 * deg, -170 * deg, -120 * deg, -175 * deg},
       {170 * deg, 120 * deg, 170 * deg, 120 * deg, 170 * deg, 120 * deg, 175 * deg},
       {320, 320, 176, 176, 110, 40, 40}},
      {"ur5e",
       {"shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"},
       {-2 * kPi, -2 * kPi, -kPi, -2 * kPi, -2 * kPi, -2 * kPi},
       {2 * kPi, 2 * kPi, kPi, 2 * kPi, 2 * kPi, 2 * kPi},
       {150, 150, 150, 28, 28, 28}},
  };
  for (const auto& r : robots) {
    ModelPtr servo = load_model_file(r.file + ".xml");
    ModelPtr motor = load_model_file(r.file + "_torque.xml");
    ASSERT_NE(servo, nullptr);
    ASSERT_NE(motor, nullptr);
    for (size_t i = 0; i < r.joints.size(); ++i) {
      const char* name = r.joints[i].c_str();
      const int j = mj_name2id(servo.get(), mjOBJ_JOINT, name);
      ASSERT_GE(j, 0) << r.file << ": " << name;
      EXPECT_NEAR(servo->jnt_range[2 * j], r.lo[i], 1e-12) << r.file << ": " << name;
      EXPECT_NEAR(servo->jnt_range[2 * j + 1], r.hi[i], 1e-12) << r.file << ": " << name;
      const int a = mj_name2id(servo.get(), mjOBJ_ACTUATOR, name);
      ASSERT_GE(a, 0) << r.file << ": actuator " << name;
      EXPECT_EQ(servo->actuator_forcerange[2 * a], -r.torque[i]) << name;
      EXPECT_EQ(servo->actuator_forcerange[2 * a + 1], r.torque[i]) << name;
      const int am = mj_name2id(motor.get(), mjOBJ_ACTUATOR, name);
      ASSERT_GE(am, 0) << r.file << "_torque: actuator " << name;
      EXPECT_EQ(motor->actuator_ctrlrange[2 * am], -r.torque[i]) << name;
      EXPECT_EQ(motor->actuator_ctrlrange[2 * am + 1], r.torque[i]) << name;
    }
  }
}

TEST(BundledModelDh, PandaHomeKeyframeIsFrankasReadyPose) {
  ModelPtr m = load_model_file("panda.xml");
  ASSERT_NE(m, nullptr);
  const int key = mj_name2id(m.get(), mjOBJ_KEY, "home");
  ASSERT_GE(key, 0);
  const std::array<double, 7> home = {0, -0.785, 0, -2.356, 0, 1.571, 0.785};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(m->key_qpos[key * m->nq + i], home[i]);
}

}  // namespace
