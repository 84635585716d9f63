#include "mjarm/kinematics/contacts.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

/// A 1 kg box resting on the floor, and a 0.5 kg box stacked on a 2 kg box beside it.
constexpr const char* kBoxes = R"(
<mujoco model="boxes">
  <option timestep="0.002"/>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.1"/>
    <body name="box" pos="0 0 0.12">
      <freejoint/>
      <geom name="box_geom" type="box" size="0.1 0.1 0.1" mass="1"/>
    </body>
    <body name="bottom" pos="1 0 0.11">
      <freejoint/>
      <geom name="bottom_geom" type="box" size="0.1 0.1 0.1" mass="2"/>
    </body>
    <body name="top" pos="1 0 0.32">
      <freejoint/>
      <geom name="top_geom" type="box" size="0.05 0.05 0.05" mass="0.5"/>
    </body>
  </worldbody>
</mujoco>
)";

class ContactsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // one second of simulation brings every box to rest
    for (int step = 0; step < 500; ++step) mj_step(&m(), d_.get());
    mj_forward(&m(), d_.get());
  }
  const mjModel& m() const { return robot_.model(); }

  Robot robot_ = Robot::from_string(kBoxes);
  DataPtr d_ = robot_.make_data();
  double g_ = 9.81;
};

TEST_F(ContactsTest, RestingBoxCarriesItsWeight) {
  const std::vector<ContactForce> contacts = contact_forces(m(), *d_);
  const int box = robot_.body("box");
  int on_box = 0;
  for (const ContactForce& c : contacts) {
    // geom ids, bodies and normals are consistent, and the normal force pushes the geoms apart
    EXPECT_EQ(c.body1, m().geom_bodyid[c.geom1]);
    EXPECT_EQ(c.body2, m().geom_bodyid[c.geom2]);
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    EXPECT_GT(c.force_W.dot(c.normal), 0.0);
    if (c.body1 == box || c.body2 == box) ++on_box;
  }
  EXPECT_GE(on_box, 1);
  const Eigen::Vector3d f = contact_force_on_body(contacts, box);
  EXPECT_LT((f - Eigen::Vector3d(0, 0, 1.0 * g_)).norm(), 1e-3 * 1.0 * g_) << f.transpose();
  // the floor feels the opposite
  const int floor = 0;
  const Eigen::Vector3d on_floor = contact_force_on_body(contacts, floor);
  EXPECT_LT((on_floor + Eigen::Vector3d(0, 0, 3.5 * g_)).norm(), 1e-3 * 3.5 * g_);
}

TEST_F(ContactsTest, RecordsNameTheGeomsAndSplitTheForce) {
  const std::vector<ContactForce> contacts = contact_forces(m(), *d_);
  ASSERT_FALSE(contacts.empty());
  int top_on_bottom = 0;
  for (const ContactForce& c : contacts) {
    EXPECT_EQ(c.geom1_name, mj_id2name(&m(), mjOBJ_GEOM, c.geom1));
    EXPECT_EQ(c.body2_name, mj_id2name(&m(), mjOBJ_BODY, c.body2));
    if (c.geom1_name == "floor") EXPECT_EQ(c.body1_name, "world");
    if (c.geom2_name == "top_geom" || c.geom1_name == "top_geom") ++top_on_bottom;
    // normal and friction parts add up to the force; the friction part is tangential
    EXPECT_LT((c.normal_force * c.normal + c.friction_W - c.force_W).norm(), 1e-12);
    EXPECT_NEAR(c.friction_W.dot(c.normal), 0.0, 1e-9);
    EXPECT_NEAR(c.normal_force, c.force_W.dot(c.normal), 1e-9);
    EXPECT_GE(c.normal_force, 0.0);
    // the frame's first row is the normal, the rows orthonormal
    EXPECT_LT((c.frame.row(0).transpose() - c.normal).norm(), 1e-15);
    EXPECT_LT((c.frame * c.frame.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-9);
    // resting boxes: the geoms touch within MuJoCo's soft penetration (under a millimetre)
    EXPECT_LT(std::abs(c.distance), 1e-3);
  }
  EXPECT_GE(top_on_bottom, 1);
}

TEST_F(ContactsTest, ARestingBoxStandsOnFourCornersThatShareItsWeight) {
  // the textbook case: a 1 kg box on a plane, four corner contacts of m·g/4 = 2.4525 N each
  std::vector<double> corners;
  for (const ContactForce& c : contact_forces(m(), *d_))
    if (c.geom2_name == "box_geom" || c.geom1_name == "box_geom") corners.push_back(c.normal_force);
  ASSERT_EQ(corners.size(), 4u);
  for (const double f : corners) EXPECT_NEAR(f, 9.81 / 4.0, 1e-3) << "of 2.4525 N";
}

TEST_F(ContactsTest, StackedBoxesLoadTheirSupports) {
  const std::vector<ContactForce> contacts = contact_forces(m(), *d_);
  const int bottom = robot_.body("bottom"), top = robot_.body("top");
  // the top box is held by the bottom one; the bottom one holds both against the floor
  EXPECT_LT((contact_force_on_body(contacts, top) - Eigen::Vector3d(0, 0, 0.5 * g_)).norm(),
            1e-3 * 0.5 * g_);
  EXPECT_LT((contact_force_on_body(contacts, bottom) - Eigen::Vector3d(0, 0, 2.0 * g_)).norm(),
            1e-3 * 2.0 * g_);
  // mujoco's own bookkeeping: cfrc_ext (rows [torque; force]) holds +f on geom2's body
  mj_rnePostConstraint(&m(), d_.get());
  for (int body : {robot_.body("box"), bottom, top}) {
    const Eigen::Vector3d f_ext = Eigen::Map<const Eigen::Vector3d>(d_->cfrc_ext + 6 * body + 3);
    EXPECT_LT((f_ext - contact_force_on_body(contacts, body)).norm(), 1e-9);
  }
}

TEST_F(ContactsTest, PairSumsEqualContactSums) {
  const std::vector<ContactForce> contacts = contact_forces(m(), *d_);
  const std::vector<BodyPairForce> pairs = sum_by_body_pair(contacts);
  ASSERT_EQ(pairs.size(), 3u);  // floor–box, floor–bottom, bottom–top
  int counted = 0;
  for (const BodyPairForce& pair : pairs) {
    EXPECT_LT(pair.body1, pair.body2);
    Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
    int n = 0;
    for (const ContactForce& c : contacts) {
      const double sign = c.body1 == pair.body1 && c.body2 == pair.body2   ? 1.0
                          : c.body1 == pair.body2 && c.body2 == pair.body1 ? -1.0
                                                                           : 0.0;
      f += sign * c.force_W;
      t += sign * c.torque_W;
      n += sign != 0.0;
    }
    EXPECT_EQ(pair.contacts, n);
    EXPECT_LT((pair.force_W - f).norm(), 1e-12);
    EXPECT_LT((pair.torque_W - t).norm(), 1e-12);
    counted += n;
  }
  EXPECT_EQ(counted, static_cast<int>(contacts.size()));
  // the sum over pairs, with each pair's sign, equals the sum over contacts
  Eigen::Vector3d net_pairs = Eigen::Vector3d::Zero(), net_contacts = Eigen::Vector3d::Zero();
  for (const BodyPairForce& pair : pairs) net_pairs += pair.force_W;
  for (const ContactForce& c : contacts) net_contacts += c.body1 < c.body2 ? c.force_W : -c.force_W;
  EXPECT_LT((net_pairs - net_contacts).norm(), 1e-12);
}

TEST(ContactPairs, FlippedContactsChangeSign) {
  ContactForce a;
  a.body1 = 2;
  a.body2 = 5;
  a.force_W = Eigen::Vector3d(1, 2, 3);
  a.torque_W = Eigen::Vector3d(0.1, 0, 0);
  ContactForce b = a;
  b.body1 = 5;
  b.body2 = 2;
  b.force_W = Eigen::Vector3d(-1, 0, 4);
  const std::vector<BodyPairForce> pairs = sum_by_body_pair({a, b});
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].body1, 2);
  EXPECT_EQ(pairs[0].body2, 5);
  EXPECT_EQ(pairs[0].contacts, 2);
  EXPECT_EQ(pairs[0].force_W, Eigen::Vector3d(2, 2, -1));
  EXPECT_EQ(pairs[0].torque_W, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(contact_force_on_body({a, b}, 5), Eigen::Vector3d(2, 2, -1));
  EXPECT_EQ(contact_force_on_body({a, b}, 2), Eigen::Vector3d(-2, -2, 1));
}

}  // namespace
}  // namespace mjarm
