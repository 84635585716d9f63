// The bound on a model's size (model_size.hpp), checked before MuJoCo compiles: MJCF files and
// strings (includes inlined, <replicate> copies counted), URDF; the bound raised and lowered.

#include "mjarm/model/model_size.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/number_text.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

/// Restores the process-wide bound when a test ends.
struct BoundGuard {
  ~BoundGuard() { set_max_model_elements(kDefaultMaxModelElements); }
};

std::string spheres(int count) {
  std::string xml = R"(<mujoco model="spheres"><worldbody><body name="b"><joint axis="0 0 1"/>)";
  for (int i = 0; i < count; ++i) xml += R"(<geom size="0.01"/>)";
  return xml + "</body></worldbody></mujoco>";
}

TEST(ModelSize, AModelBeyondTheBoundIsRefusedNamingItsKinds) {
  const BoundGuard guard;
  EXPECT_EQ(max_model_elements(), kDefaultMaxModelElements);
  const std::string message = error_of([] { Robot::from_string(spheres(20000)); });
  EXPECT_NE(message.find("the MJCF text has 20003 elements (20000 geom, 1 body, 1 joint), more "
                         "than the 20000 a model may have"),
            std::string::npos)
      << message;
  // lowered, a small model is refused; raised, it loads (a small count: compiling is the cost)
  set_max_model_elements(100);
  EXPECT_NE(error_of([] { Robot::from_string(spheres(150)); }).find("more than the 100"),
            std::string::npos);
  set_max_model_elements(200);
  EXPECT_NO_THROW(Robot::from_string(spheres(150)));
  set_max_model_elements(2);
  EXPECT_NE(error_of([] { Robot::bundled("planar2"); }).find("more than the 2 a model may have"),
            std::string::npos);
  EXPECT_NE(error_of([] { set_max_model_elements(0); }).find("from 1 to 100000000, got 0"),
            std::string::npos);
}

TEST(ModelSize, ReplicatedElementsCountEveryCopy) {
  const BoundGuard guard;
  const std::string message = error_of([] {
    Robot::from_string(R"(<mujoco><worldbody>
      <replicate count="200" offset="0.1 0 0"><replicate count="200" offset="0 0.1 0">
        <body><joint axis="0 0 1"/><geom size="0.01"/></body>
      </replicate></replicate></worldbody></mujoco>)");
  });
  EXPECT_NE(message.find("120202 elements (40000 body, 40000 geom, 40000 joint)"),
            std::string::npos)
      << message;
}

TEST(ModelSize, UrdfIsCountedToo) {
  const BoundGuard guard;
  set_max_model_elements(3);
  const std::string message = error_of([] {
    Robot::from_string(R"(<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)");
  });
  EXPECT_NE(message.find("model XML string has 6 elements"), std::string::npos) << message;
}

TEST(NumberText, TheShortestFormThatReadsBackTheSame) {
  EXPECT_EQ(number_text(1e308), "1e+308");
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(250.0), "250");
  EXPECT_EQ(number_text(-2.5e-7), "-2.5e-07");
  EXPECT_EQ(number_text(2.8973), "2.8973");
  EXPECT_EQ(number_text(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(number_text(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity()), "-inf");
}

}  // namespace
}  // namespace mjarm
