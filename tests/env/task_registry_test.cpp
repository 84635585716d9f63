// The task registry: every name builds its task; an unknown name suggests the closest.

#include "mjarm/env/task_registry.hpp"

#include <gtest/gtest.h>

#include "env/env_test_support.hpp"

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

}  // namespace
}  // namespace mjarm
