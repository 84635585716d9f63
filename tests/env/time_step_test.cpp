// The Observation view of a time step, and the names of step types and episode ends.

#include "mjarm/env/time_step.hpp"

#include <gtest/gtest.h>

#include "env/env_test_support.hpp"

namespace mjarm {
namespace {

TEST(Observation, ViewsTheArraysByNameAndIndex) {
  const ObservationSpec spec({ArraySpec::vector("a", 2), ArraySpec::vector("b", 3)});
  const std::vector<double> values{1, 2, 3, 4, 5};
  const Observation o(&spec, values);
  ASSERT_EQ(o["b"].size(), 3u);
  EXPECT_EQ(o["b"][0], 3.0);
  EXPECT_EQ(o.at(0)[1], 2.0);
  EXPECT_EQ(o.values().size(), 5u);
  test::expect_error_containing([&] { o["c"]; }, {"'c'"});
  test::expect_error_containing([&] { o.at(2); }, {"index 2 out of range"});
  test::expect_error_containing([] { Observation().at(0); }, {"no reset yet"});
  EXPECT_STREQ(to_string(StepType::last), "last");
  EXPECT_STREQ(to_string(EpisodeEnd::truncated), "truncated");
}

}  // namespace
}  // namespace mjarm
