#include "mjarm/dynamics/force_torque_sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/error_message.hpp"

namespace mjarm {
namespace {

// a tool (0.5 kg, centre of mass off the site) on a fixed mount, the sensor site rotated; and a
// two-joint arm carrying the same tool, to see the timing of the reading while it moves
constexpr const char* kFtScene = R"(
<mujoco model="ft_scene">
  <option timestep="0.002" integrator="Euler"/>
  <worldbody>
    <body name="mount" pos="0.2 -0.1 0.5" euler="0.3 0 0.2">
      <geom type="box" size="0.05 0.05 0.05" mass="1"/>
      <body name="tool" pos="0 0 -0.1" euler="0 0.4 0">
        <inertial pos="0.02 -0.01 -0.05" mass="0.5" diaginertia="0.001 0.001 0.001"/>
        <site name="ft" pos="0 0 0" euler="0.1 -0.2 0.7"/>
        <site name="bare"/>
      </body>
    </body>
    <body name="arm" pos="0 0.6 0.5">
      <joint name="a1" axis="0 0 1"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
      <body name="forearm" pos="0.3 0 0">
        <joint name="a2" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
        <body name="arm_tool" pos="0.3 0 0">
          <inertial pos="0.03 0 -0.02" mass="0.4" diaginertia="0.001 0.001 0.001"/>
          <site name="arm_ft" euler="0.2 0.1 0"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="a1"/>
    <motor joint="a2"/>
  </actuator>
  <sensor>
    <force site="ft"/>
    <torque site="ft"/>
    <force site="arm_ft"/>
    <torque site="arm_ft"/>
    <force site="bare"/>
  </sensor>
</mujoco>
)";

using RowMajorRotation = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Eigen::Vector3d ft_vec(const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); }

TEST(ForceTorqueSensor, StaticToolReadsItsWeightAndThePushAgainstIt) {
  const Robot robot = Robot::from_string(kFtScene);
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  const ForceTorqueSensor sensor(robot, "ft", SensorTiming::after_forward);
  const int tool = mj_name2id(&m, mjOBJ_BODY, "tool");

  // nothing touching: the mount holds the tool's weight up, f = −m·gravity (+4.905 N along z)
  mj_forward(&m, d.get());
  const Eigen::Vector3d c = ft_vec(d->xipos + 3 * tool);
  WrenchReading held = sensor.read_world(*d, c);
  ASSERT_TRUE(held.ok());
  EXPECT_NEAR(held.wrench[2], 0.5 * 9.81, 1e-9);
  EXPECT_LT(held.wrench.head<2>().norm(), 1e-9);
  EXPECT_LT(held.wrench.tail<3>().norm(), 1e-9);  // about the centre of mass: no moment

  // a push F_ext at the centre of mass: the reading is −(weight + F_ext), about any point
  const Eigen::Vector3d f_ext(3.0, -2.0, 1.5);
  const Eigen::Vector3d n_ext(0.2, 0.1, -0.3);
  for (int k = 0; k < 3; ++k) {
    d->xfrc_applied[6 * tool + k] = f_ext[k];
    d->xfrc_applied[6 * tool + 3 + k] = n_ext[k];
  }
  mj_forward(&m, d.get());
  const Eigen::Vector3d f_total = f_ext + 0.5 * ft_vec(m.opt.gravity);
  const Eigen::Vector3d p_S = ft_vec(d->site_xpos + 3 * sensor.site_id());
  const Eigen::Vector3d p_P(0.4, 0.3, -0.2);
  const WrenchReading at_P = sensor.read_world(*d, p_P);
  ASSERT_TRUE(at_P.ok());
  EXPECT_LT((at_P.wrench.head<3>() + f_total).norm(), 1e-9);
  EXPECT_LT((at_P.wrench.tail<3>() + n_ext + (c - p_P).cross(f_total)).norm(), 1e-9);

  // the raw reading is in the site's axes about its origin
  const RowMajorRotation R_WS =
      Eigen::Map<const RowMajorRotation>(d->site_xmat + 9 * sensor.site_id());
  const WrenchReading raw = sensor.read_site(*d);
  EXPECT_LT((R_WS * raw.wrench.head<3>() + f_total).norm(), 1e-9);
  EXPECT_LT((R_WS * raw.wrench.tail<3>() + n_ext + (c - p_S).cross(f_total)).norm(), 1e-9);

  // body axes: the world reading seen from E
  Pose X_WE;
  X_WE.p = p_P;
  X_WE.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const WrenchReading body = sensor.read_body(*d, X_WE);
  EXPECT_LT((X_WE.R * body.wrench.head<3>() - at_P.wrench.head<3>()).norm(), 1e-12);
  EXPECT_LT((X_WE.R * body.wrench.tail<3>() - at_P.wrench.tail<3>()).norm(), 1e-12);
}

TEST(ForceTorqueSensor, ShiftWrenchMovesTheMomentPoint) {
  Vector6d F;
  F << 1, 2, 3, 0.1, 0.2, 0.3;
  const Eigen::Vector3d a(0.5, -0.2, 0.1);
  const Eigen::Vector3d b(-0.3, 0.4, 0.9);
  const Vector6d moved = shift_wrench(F, a, b);
  EXPECT_EQ(moved.head<3>(), F.head<3>());
  EXPECT_LT((moved.tail<3>() - (F.tail<3>() + (a - b).cross(F.head<3>()))).norm(), 1e-15);
  EXPECT_LT((shift_wrench(moved, b, a) - F).norm(), 1e-14);  // and back
}

TEST(ForceTorqueSensor, AfterAStepTheReadingIsOneStepOld) {
  const Robot robot = Robot::from_string(kFtScene);
  const mjModel& m = robot.model();
  DataPtr d = robot.make_data();
  DataPtr before = robot.make_data();
  const ForceTorqueSensor sensor(robot, "arm_ft");
  EXPECT_EQ(sensor.timing(), SensorTiming::after_step);
  d->qvel[0] = 1.0;
  d->qvel[1] = -2.0;
  for (int k = 0; k < 20; ++k) {
    d->ctrl[0] = std::sin(0.3 * k);
    d->ctrl[1] = std::cos(0.2 * k);
    // the state the step starts from, forwarded on its own: what the sensor saw
    mj_copyData(before.get(), &m, d.get());
    mj_forward(&m, before.get());
    mj_step(&m, d.get());
    const WrenchReading r = sensor.read_site(*d);
    ASSERT_TRUE(r.ok());
    EXPECT_DOUBLE_EQ(r.age, m.opt.timestep);
    EXPECT_DOUBLE_EQ(r.time, before->time);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(r.wrench[i], before->sensordata[6 + i]) << i;
    // Simulation's split step runs controllers after mj_step1, which leaves the value alone
    mj_step1(&m, d.get());
    for (int i = 0; i < 6; ++i) EXPECT_EQ(sensor.read_site(*d).wrench[i], r.wrench[i]) << i;
    // and it differs from the state it is read at: the arm accelerates
    mj_copyData(before.get(), &m, d.get());
    mj_forward(&m, before.get());
    EXPECT_GT(std::abs(r.wrench[0] - before->sensordata[6]) +
                  std::abs(r.wrench[3] - before->sensordata[9]),
              1e-9);
  }
}

TEST(ForceTorqueSensor, MissingSensorsAndSitesNameTheSite) {
  const Robot robot = Robot::from_string(kFtScene);
  const std::string no_torque = test::error_of([&] { ForceTorqueSensor(robot, "bare"); });
  EXPECT_NE(no_torque.find("site 'bare'"), std::string::npos) << no_torque;
  EXPECT_NE(no_torque.find("no torque sensor"), std::string::npos) << no_torque;
  const std::string unknown = test::error_of([&] { ForceTorqueSensor(robot, "flange"); });
  EXPECT_NE(unknown.find("'flange'"), std::string::npos) << unknown;
  const Robot iiwa = Robot::bundled("iiwa14");
  const std::string none = test::error_of([&] { ForceTorqueSensor(iiwa, "attachment_site"); });
  EXPECT_NE(none.find("site 'attachment_site' of model 'iiwa14' has no force sensor"),
            std::string::npos)
      << none;
}

TEST(ForceTorqueSensor, NonFiniteReadingsGiveAnHonestStatus) {
  const Robot robot = Robot::from_string(kFtScene);
  DataPtr d = robot.make_data();
  mj_forward(&robot.model(), d.get());
  const ForceTorqueSensor sensor(robot, "ft");
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (int i = 0; i < 6; ++i) {
      mj_forward(&robot.model(), d.get());
      d->sensordata[i] = bad;
      for (const WrenchReading& r :
           {sensor.read_site(*d), sensor.read_world(*d, Eigen::Vector3d::Zero()),
            sensor.read_body(*d, Pose{})}) {
        EXPECT_EQ(r.status, WrenchStatus::non_finite);
        EXPECT_EQ(r.wrench, Vector6d::Zero());
      }
    }
  }
  EXPECT_STREQ(to_string(WrenchStatus::non_finite), "non_finite");
}

}  // namespace
}  // namespace mjarm
