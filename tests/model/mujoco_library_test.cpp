#include "mjarm/model/mujoco_library.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

TEST(MujocoLibrary, VersionNumbersReadAsMajorMinorPatch) {
  EXPECT_EQ(mujoco_version_text(4000001), "4.0.1");
  EXPECT_EQ(mujoco_version_text(3003006), "3.3.6");
  EXPECT_EQ(mujoco_version_text(12034005), "12.34.5");
  EXPECT_EQ(mujoco_version_text(mj_version()), mj_versionString());
}

TEST(MujocoLibrary, TheLibraryLoadedIsTheOneCompiledFor) {
  EXPECT_NO_THROW(check_mujoco_library());
  const auto path = mujoco_library_path();
  EXPECT_EQ(path.filename().string().rfind("libmujoco", 0), 0U) << path;
}

TEST(MujocoLibrary, ARobotSharesAModelCompiledElsewhere) {
  mjModel* compiled = mj_loadXML(
      (Robot::models_dir() / "planar2.xml").c_str(), nullptr, nullptr, 0);
  ASSERT_NE(compiled, nullptr);
  bool released = false;
  {
    const Robot robot = Robot::from_model(
        std::shared_ptr<const mjModel>(compiled,
                                       [&](const mjModel* m) {
                                         released = true;
                                         mj_deleteModel(const_cast<mjModel*>(m));
                                       }),
        "a test's mjModel");
    EXPECT_EQ(&robot.model(), compiled);  // the same struct, not a copy
    EXPECT_EQ(robot.source(), "a test's mjModel");
    const Robot copy = robot;
    EXPECT_FALSE(released);
  }
  EXPECT_TRUE(released);
  EXPECT_THROW(Robot::from_model(nullptr, "nothing"), Error);
}

}  // namespace
}  // namespace mjarm
