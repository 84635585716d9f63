// URDF names (issue 29, item 1 in URDF): MuJoCo's URDF reader skips elements and attributes it
// does not know and reads the first of a repeated one; a misspelt <axis> left a joint turning
// about x, `rpyy` an origin unrotated, <colision> a link without collision geometry, exit 0.
#include <gtest/gtest.h>

#include <string>

#include "mjarm/model/robot.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using test::error_of;

// a two-link URDF: @p link goes into link "arm", @p joint into joint "shoulder"
std::string urdf(const std::string& link, const std::string& joint) {
  return "<robot name=\"r\">\n"
         "  <link name=\"base\"/>\n"
         "  <link name=\"arm\">\n"
         "    <inertial><mass value=\"1\"/>"
         "<inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>\n"
         "    " +
         link +
         "\n"
         "  </link>\n"
         "  <joint name=\"shoulder\" type=\"revolute\">\n"
         "    <parent link=\"base\"/><child link=\"arm\"/>\n"
         "    " +
         joint +
         "\n"
         "    <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n"
         "  </joint>\n"
         "</robot>\n";
}

const std::string kBox =
    "<collision><origin xyz=\"0 0 0.1\" rpy=\"0 0 0\"/>"
    "<geometry><box size=\"0.1 0.1 0.2\"/></geometry></collision>";

bool says(const std::string& message, const std::string& part) {
  return message.find(part) != std::string::npos;
}

TEST(UrdfNames, AWellFormedUrdfLoads) {
  const Robot robot =
      Robot::from_string(urdf(kBox, "<origin xyz=\"0 0 1\"/><axis xyz=\"0 1 0\"/>"));
  EXPECT_EQ(robot.model().ngeom, 1);
  EXPECT_EQ(robot.model().jnt_axis[1], 1.0);
  EXPECT_TRUE(robot.load_warnings().empty());
}

TEST(UrdfNames, UnknownElementsAndAttributesNameTheLineAndTheClosest) {
  std::string message = error_of([] {
    Robot::from_string(urdf("<colision><geometry><sphere radius=\"0.1\"/></geometry></colision>",
                            "<axis xyz=\"0 1 0\"/>"));
  });
  EXPECT_TRUE(says(message,
                   "URDF XML string line 5: unknown element 'colision' in link 'arm'; "
                   "closest: collision; elements: inertial, visual, collision"))
      << message;
  message = error_of([] { Robot::from_string(urdf(kBox, "<axs xyz=\"0 1 0\"/>")); });
  EXPECT_TRUE(says(message, "line 9: unknown element 'axs' in joint 'shoulder'; closest: axis"))
      << message;
  message =
      error_of([] { Robot::from_string(urdf(kBox, "<origin xyz=\"0 0 1\" rpyy=\"1 0 0\"/>")); });
  EXPECT_TRUE(says(message,
                   "line 9: unknown attribute 'rpyy' in <origin> of joint 'shoulder'; "
                   "closest: rpy; attributes: xyz, rpy"))
      << message;
  message = error_of([] {
    Robot::from_string(
        urdf("<visual><geometry><cylinder radius=\"0.1\" lenght=\"1\"/></geometry>"
             "</visual>",
             ""));
  });
  EXPECT_TRUE(says(message,
                   "unknown attribute 'lenght' in <cylinder> of <geometry> of <visual> "
                   "of link 'arm'; closest: length"))
      << message;
}

TEST(UrdfNames, RepeatedElementsAndSecondShapesAreRefused) {
  std::string message = error_of(
      [] { Robot::from_string(urdf(kBox, "<axis xyz=\"0 1 0\"/>\n    <axis xyz=\"1 0 0\"/>")); });
  EXPECT_TRUE(says(message,
                   "line 10: a second <axis> in joint 'shoulder' (the first at line 9): "
                   "MuJoCo reads only the first"))
      << message;
  message = error_of([] {
    Robot::from_string(urdf(
        "<visual><geometry><box size=\"1 1 1\"/><sphere radius=\"1\"/></geometry></visual>", ""));
  });
  EXPECT_TRUE(says(message,
                   "a second shape <sphere> in <geometry> of <visual> of link 'arm' (the "
                   "first, <box>, at line 5): a geometry holds one"))
      << message;
  // several visuals and collisions are URDF
  EXPECT_EQ(Robot::from_string(urdf(kBox + kBox, "")).model().ngeom, 2);
}

TEST(UrdfNames, OtherSchemasAndSimulatorsAreLeftToThem) {
  // namespaced names, extensions beside the links, Bullet's <contact> (a load warning)
  const Robot robot = Robot::from_string(
      "<robot name=\"r\" xmlns:drake=\"http://drake.mit.edu\">\n"
      "  <gazebo reference=\"base\"><mu1>0.5</mu1></gazebo>\n"
      "  <transmission name=\"t\"><type>x</type></transmission>\n"
      "  <link name=\"base\">\n"
      "    <contact><lateral_friction value=\"1\"/></contact>\n"
      "    <collision><geometry><box size=\"1 1 1\"/></geometry>"
      "<drake:proximity_properties/></collision>\n"
      "  </link>\n"
      "</robot>\n");
  ASSERT_EQ(robot.load_warnings().size(), 1u);
  EXPECT_TRUE(says(robot.load_warnings()[0],
                   "URDF XML string line 5: <contact> in link 'base' is not "
                   "URDF (another simulator's); MuJoCo ignores it"))
      << robot.load_warnings()[0];
}

}  // namespace
}  // namespace mjarm
