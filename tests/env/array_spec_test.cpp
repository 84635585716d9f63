// ArraySpec and ObservationSpec: sizes, offsets, bounds checks, names.

#include "mjarm/env/array_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "env/env_test_support.hpp"

namespace mjarm {
namespace {

TEST(ArraySpec, SizesBoundsAndDescription) {
  const ArraySpec v = ArraySpec::vector("v", 4);
  EXPECT_EQ(v.size(), 4);
  EXPECT_FALSE(v.bounded());
  EXPECT_EQ(v.describe(), "v: float64[4] in [-inf, inf]");
  const ArraySpec b =
      ArraySpec::bounded("b", Eigen::Vector2d(-1.0, 0.0), Eigen::Vector2d(1.0, 2.5));
  EXPECT_TRUE(b.bounded());
  EXPECT_EQ(b.describe(), "b: float64[2] in [-1, 1], [0, 2.5]");
  ArraySpec matrix{"m", {2, 3}, DType::float64, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Ones(6)};
  EXPECT_EQ(matrix.size(), 6);
  EXPECT_NO_THROW(matrix.check());
  ArraySpec scalar{"s", {}, DType::float64, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1)};
  EXPECT_EQ(scalar.size(), 1);
  EXPECT_STREQ(to_string(DType::float64), "float64");
}

TEST(ArraySpec, CheckNamesWhatIsWrong) {
  ArraySpec s = ArraySpec::vector("x", 2);
  s.minimum[1] = 3.0;
  s.maximum[1] = 2.0;
  test::expect_error_containing([&] { s.check(); }, {"'x'", "element 1", "[3, 2]"});
  s = ArraySpec::vector("x", 2);
  s.minimum[0] = std::numeric_limits<double>::quiet_NaN();
  test::expect_error_containing([&] { s.check(); }, {"element 0", "NaN"});
  s = ArraySpec::vector("x", 2);
  s.shape = {3};
  test::expect_error_containing([&] { s.check(); }, {"bounds need 3 entries"});
  s.shape = {0};
  test::expect_error_containing([&] { s.check(); }, {"dimension 0"});
  test::expect_error_containing([] { ArraySpec::vector("", 1).check(); }, {"name is empty"});
}

TEST(ObservationSpec, LaysArraysBackToBack) {
  const ObservationSpec spec(
      {ArraySpec::vector("a", 3), ArraySpec::vector("b", 1), ArraySpec::vector("c", 7)});
  EXPECT_EQ(spec.count(), 3);
  EXPECT_EQ(spec.size(), 11);
  EXPECT_EQ(spec.offset(0), 0);
  EXPECT_EQ(spec.offset(1), 3);
  EXPECT_EQ(spec.offset(2), 4);
  EXPECT_EQ(spec.index("c"), 2);
  EXPECT_EQ(spec.find("d"), -1);
  EXPECT_EQ(spec.names(), (std::vector<std::string>{"a", "b", "c"}));
  test::expect_error_containing([&] { spec.index("bb"); },
                                {"'bb' is not in this observation", "closest: b", "a, b, c"});
  test::expect_error_containing(
      [] {
        ObservationSpec twice({ArraySpec::vector("a", 1), ArraySpec::vector("a", 2)});
      },
      {"'a' is listed twice"});
}

}  // namespace
}  // namespace mjarm
