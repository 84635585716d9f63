// Declared fields as data (mjarm/field_table.hpp): the flattened table with kinds, units, ranges,
// names and values, and one field set by its path from JSON or from a command-line word, with
// JSON input's checks and messages.
#include "mjarm/field_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm::field_table_test {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

enum class Grasp { weld, friction };

constexpr auto declared_names(const Grasp*) {
  return std::array{EnumName{Grasp::weld, "weld"}, EnumName{Grasp::friction, "friction"}};
}

struct Limits {
  double rest_speed = 0.001;
  double time_limit = Range::inf;
};

constexpr auto declared_fields(const Limits*) {
  using S = Limits;
  return declare<S>(
      "limits", field("rest_speed", &S::rest_speed, "m/s", Range::positive(), "at the end"),
      field("time_limit", &S::time_limit, "s", Range::positive().or_infinity(), "+inf: none"));
}

struct Trial {
  double object_size = 0.02;
  int trials = 25;
  bool classic = false;
  std::string robot = "arm6";
  Grasp grasp = Grasp::weld;
  Eigen::Vector3d target{0.4, 0.0, 0.3};
  std::vector<double> gains{1.0, 2.0};
  Limits limits;
};

constexpr auto declared_fields(const Trial*) {
  using S = Trial;
  return declare<S>(
      "trial", field("object_size", &S::object_size, "m", Range::closed(0.005, 0.05), "cube edge"),
      field("trials", &S::trials, "", Range::at_least(1), "how many"),
      field("classic", &S::classic, "the old scene"), field("robot", &S::robot, "bundled arm"),
      field("grasp", &S::grasp, "how the object is held"),
      field("target", &S::target, "m", Range::finite(), "where it goes"),
      field("gains", &S::gains, "", Range::non_negative(), "per joint"),
      field("limits", &S::limits, "when it ends"));
}

std::string set_message(std::string_view path, std::string_view text) {
  Trial t;
  try {
    set_field_text(t, path, text, "--x");
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(FieldTable, ListsEveryFieldFlattenedWithItsDeclaration) {
  Trial t;
  t.limits.rest_speed = 0.002;
  const std::vector<FieldInfo> table = field_table(t);
  std::vector<std::string> paths;
  for (const FieldInfo& info : table) paths.push_back(info.path);
  EXPECT_THAT(paths, ElementsAre("object_size", "trials", "classic", "robot", "grasp", "target",
                                 "gains", "limits.rest_speed", "limits.time_limit"));
  EXPECT_EQ(table[0].kind, FieldKind::number);
  EXPECT_EQ(table[0].unit, "m");
  EXPECT_EQ(table[0].range.text(), "in [0.005, 0.05]");
  EXPECT_EQ(table[0].doc, "cube edge");
  EXPECT_EQ(table[0].value, 0.02);
  EXPECT_EQ(table[1].kind, FieldKind::integer);
  EXPECT_EQ(table[2].kind, FieldKind::flag);
  EXPECT_EQ(table[3].kind, FieldKind::text);
  EXPECT_EQ(table[4].kind, FieldKind::name);
  EXPECT_THAT(table[4].names, ElementsAre("weld", "friction"));
  EXPECT_EQ(table[4].value, "weld");
  EXPECT_EQ(table[5].kind, FieldKind::numbers);
  EXPECT_EQ(table[5].length, 3);
  EXPECT_EQ(table[6].length, -1);
  EXPECT_EQ(table[7].value, 0.002);       // the value in the struct listed, not the default
  EXPECT_TRUE(table[8].value.is_null());  // +inf, as JSON writes it
  EXPECT_EQ(to_string(FieldKind::numbers), std::string("numbers"));
}

TEST(FieldTable, SetsEachKindFromACommandLineWord) {
  Trial t;
  set_field_text(t, "object_size", "0.03", "--object-size");
  set_field_text(t, "trials", "7", "--trials");
  set_field_text(t, "classic", "true", "--classic");
  set_field_text(t, "robot", "panda", "--robot");
  set_field_text(t, "grasp", "friction", "--grasp");
  set_field_text(t, "target", "0.5, -0.1,0.2", "--target");
  set_field_text(t, "gains", "3", "--gains");
  set_field_text(t, "limits.rest_speed", "2e-3", "--rest-speed");
  set_field_text(t, "limits.time_limit", "inf", "--time-limit");
  EXPECT_EQ(t.object_size, 0.03);
  EXPECT_EQ(t.trials, 7);
  EXPECT_TRUE(t.classic);
  EXPECT_EQ(t.robot, "panda");
  EXPECT_EQ(t.grasp, Grasp::friction);
  EXPECT_EQ(t.target, Eigen::Vector3d(0.5, -0.1, 0.2));
  EXPECT_THAT(t.gains, ElementsAre(3.0));
  EXPECT_EQ(t.limits.rest_speed, 2e-3);
  EXPECT_EQ(t.limits.time_limit, Range::inf);
  set_field_text(t, "limits.time_limit", "12.5", "--time-limit");
  EXPECT_EQ(t.limits.time_limit, 12.5);
}

TEST(FieldTable, SetsFromJsonAsJsonInputIsRead) {
  Trial t;
  set_field(t, "grasp", "friction", "sweep.yaml");
  set_field(t, "target", {0.1, 0.2, 0.3}, "sweep.yaml");
  EXPECT_EQ(t.grasp, Grasp::friction);
  EXPECT_EQ(t.target, Eigen::Vector3d(0.1, 0.2, 0.3));
  try {
    set_field(t, "limits.rest_speed", "fast", "sweep.yaml");
    FAIL() << "a string for a number was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "sweep.yaml: limits.rest_speed must be a number, got string");
  }
}

TEST(FieldTable, RefusesWhatIsNotTheFieldsKindOrRangeAndLeavesTheStructAsItWas) {
  EXPECT_EQ(set_message("object_size", "0.5"),
            "--x: object_size must be in [0.005, 0.05] [m], got 0.5");
  EXPECT_EQ(set_message("object_size", "big"), "--x: object_size must be a number, got 'big'");
  EXPECT_EQ(set_message("object_size", "0.02 "), "--x: object_size must be a number, got '0.02 '");
  EXPECT_EQ(set_message("object_size", "inf"),
            "--x: object_size must be in [0.005, 0.05] [m], got inf");
  EXPECT_EQ(set_message("limits.rest_speed", "nan"),
            "--x: limits.rest_speed must be positive and finite [m/s], got nan");
  EXPECT_EQ(set_message("trials", "2.5"), "--x: trials must be a whole number, got '2.5'");
  EXPECT_EQ(set_message("trials", "0"), "--x: trials must be ≥ 1, got 0");
  EXPECT_EQ(set_message("classic", "yes"), "--x: classic must be true or false, got 'yes'");
  EXPECT_THAT(set_message("grasp", "weld2"), HasSubstr("unknown grasp 'weld2'"));
  EXPECT_THAT(set_message("grasp", "weld2"), HasSubstr("closest: weld"));
  EXPECT_EQ(set_message("target", "0.1,0.2"), "--x: target must have 3 numbers, got 2");
  EXPECT_EQ(set_message("target", "0.1,,0.2"), "--x: target must be a number, got ''");
  EXPECT_EQ(set_message("gains", "1,-1"), "--x: gains[1] must be finite and ≥ 0, got -1");
  EXPECT_THAT(set_message("object-size", "0.02"),
              HasSubstr("--x: unknown field 'object-size'; closest: object_size"));
  EXPECT_THAT(set_message("limits.rest", "1"), HasSubstr("closest: limits.rest_speed"));

  Trial t;
  EXPECT_THROW(set_field_text(t, "gains", "1,2,-3", "--gains"), Error);
  EXPECT_THAT(t.gains, ElementsAre(1.0, 2.0));  // unchanged by a refused value
}

struct Draw {
  std::optional<double> half_size;              // drawn from the seed when not set
  std::optional<std::array<double, 2>> object;  // x y, drawn when not set
};

constexpr auto declared_fields(const Draw*) {
  using S = Draw;
  return declare<S>("draw",
                    field("half_size", &S::half_size, "m", Range::closed(0.005, 0.05), "cube"),
                    field("object", &S::object, "m", Range::finite(), "where it starts"));
}

TEST(FieldTable, AnOptionalFieldIsSetChecked_AndClearedByNone) {
  Draw d;
  std::vector<FieldInfo> table = field_table(d);
  ASSERT_EQ(table.size(), 2u);
  EXPECT_TRUE(table[0].optional);
  EXPECT_EQ(table[0].kind, FieldKind::number);
  EXPECT_EQ(table[1].kind, FieldKind::numbers);
  EXPECT_EQ(table[1].length, 2);
  EXPECT_TRUE(table[0].value.is_null());

  set_field_text(d, "half_size", "0.02", "--half-size");
  set_field_text(d, "object", "0.4,-0.1", "--object");
  ASSERT_TRUE(d.half_size && d.object);
  EXPECT_EQ(*d.half_size, 0.02);
  EXPECT_EQ((*d.object)[1], -0.1);
  EXPECT_EQ(fields_to_json(d).dump(), R"({"half_size":0.02,"object":[0.4,-0.1]})");
  try {
    set_field_text(d, "half_size", "0.5", "--half-size");
    FAIL() << "a value out of range was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "--half-size: half_size must be in [0.005, 0.05] [m], got 0.5");
  }
  EXPECT_EQ(*d.half_size, 0.02);
  set_field_text(d, "half_size", "none", "--half-size");
  set_field(d, "object", nullptr, "sweep.yaml");
  EXPECT_FALSE(d.half_size || d.object);
  EXPECT_EQ(fields_to_json(d).dump(), R"({"half_size":null,"object":null})");
}

TEST(NumberFromText, ReadsAWholeNumberAndNothingElse) {
  EXPECT_EQ(number_from_text("0.1"), 0.1);
  EXPECT_EQ(number_from_text("-2.5e-07"), -2.5e-07);
  EXPECT_EQ(number_from_text("inf"), Range::inf);
  EXPECT_EQ(number_from_text("+2"), 2.0);
  EXPECT_FALSE(number_from_text("+-2"));
  EXPECT_FALSE(number_from_text("+"));
  EXPECT_FALSE(number_from_text("0x10"));
  EXPECT_FALSE(number_from_text(""));
  EXPECT_FALSE(number_from_text(" 1"));
  EXPECT_FALSE(number_from_text("1,5"));
  EXPECT_FALSE(number_from_text("1e999"));
}

}  // namespace
}  // namespace mjarm::field_table_test
