#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mjarm/model/robot.hpp"
#include "support/error_message.hpp"
#include "support/files.hpp"

namespace mjarm {
namespace {

// a URDF naming its mesh the usual ROS way; MuJoCo strips the path and looks next to the file
constexpr const char* kUrdfWithMesh = R"(<?xml version="1.0"?>
<robot name="meshy">
  <link name="base">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="package://meshy/meshes/shell.stl"/></geometry></collision>
  </link>
</robot>)";

TEST(UrdfAssets, MeshesAreCheckedBeforeMujocoOpensThem) {
  const auto dir = test::scratch() / "urdf_assets";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "meshy.urdf") << kUrdfWithMesh;
  // MuJoCo would read /dev/zero until memory runs out
  std::filesystem::create_symlink("/dev/zero", dir / "shell.stl");
  const std::string message = test::error_of([&] { Robot::from_file(dir / "meshy.urdf"); });
  EXPECT_NE(message.find("mesh (line 5)"), std::string::npos) << message;
  EXPECT_NE(message.find("shell.stl' is a character device"), std::string::npos) << message;
  // a missing mesh is still MuJoCo's to report
  std::filesystem::remove(dir / "shell.stl");
  const std::string missing = test::error_of([&] { Robot::from_file(dir / "meshy.urdf"); });
  EXPECT_NE(missing.find("shell.stl"), std::string::npos) << missing;
  EXPECT_EQ(missing.find("character device"), std::string::npos) << missing;
}

}  // namespace
}  // namespace mjarm
