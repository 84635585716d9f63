// The task registry: every name builds its task; an unknown name suggests the closest; each
// task's options as parameters, set by name and checked as a scenario's.

#include "mjarm/env/task_registry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "env/env_test_support.hpp"
#include "mjarm/env/docking_env_task.hpp"
#include "mjarm/env/reach_task.hpp"

namespace mjarm {
namespace {

TEST(TaskRegistry, EveryNameBuildsItsTask) {
  for (const std::string& name : env_task_names()) {
    const std::unique_ptr<EnvTask> task = make_env_task(name);
    EXPECT_EQ(task->name(), name);
    EXPECT_FALSE(task->description().empty());
    EXPECT_GE(task->chain().size(), 1);
    const std::unique_ptr<EnvTask> copy = task->clone();
    EXPECT_EQ(&copy->robot().model(), &task->robot().model());  // the model is shared
  }
  test::expect_error_containing(
      [] { make_env_task("shelf_pick"); },
      {"unknown task 'shelf_pick'", "did you mean 'shelf-pick'", "tasks: reach, shelf-pick"});
}

TEST(TaskRegistry, EachTasksOptionsAreParametersSetByName) {
  for (const std::string& name : env_task_names()) EXPECT_FALSE(env_task_parameters(name).empty());
  const std::vector<FieldInfo> docking = env_task_parameters("docking");
  const auto find = [&](const std::string& path) {
    for (const FieldInfo& p : docking)
      if (p.path == path) return p;
    throw Error("no parameter " + path);
  };
  EXPECT_EQ(find("criteria.max-force").unit, "N");
  EXPECT_EQ(find("scene.geometry.chamfer").value, DockingGeometry{}.chamfer);
  EXPECT_EQ(find("offset-range.dx").value, DockingEnvOptions{}.offset_range.dx);

  const nlohmann::ordered_json values{
      {"criteria.max-force", 25.0}, {"scene.geometry.chamfer", 0.012}, {"seated_time", 0.1}};
  const std::unique_ptr<EnvTask> task = make_env_task("docking", values);
  const auto& dock = dynamic_cast<const DockingEnvTask&>(*task);
  EXPECT_EQ(dock.options().criteria.max_force, 25.0);
  EXPECT_EQ(dock.scene().options.geometry.chamfer, 0.012);  // the scene is built from them
  EXPECT_EQ(dock.options().seated_time, 0.1);

  const auto reach = make_env_task("reach", {{"success-distance", 0.02}});
  EXPECT_EQ(dynamic_cast<const ReachTask&>(*reach).options().success_distance, 0.02);

  test::expect_error_containing(
      [] {
        make_env_task("docking", {{"criteria.max-forse", 1.0}});
      },
      {"env docking: unknown parameter 'criteria.max-forse'", "closest: criteria.max-force"});
  test::expect_error_containing(
      [] {
        make_env_task("reach", {{"success-distance", -1.0}});
      },
      {"env reach: success_distance must be"});
  test::expect_error_containing(
      [] {
        make_env_task("docking", {{"offset-range.dx", -0.01}});
      },
      {"offset_range needs dx, dy in [0, 0.05] m"});
}

}  // namespace
}  // namespace mjarm
