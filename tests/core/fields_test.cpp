// Declared fields and enums (mjarm/fields.hpp, fields_json.hpp): the range wording, checks with
// the field's path, enum names both ways, strict JSON in and out.
#include "mjarm/fields.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mjarm/error.hpp"
#include "mjarm/fields_json.hpp"

namespace mjarm::fields_test {
namespace {

using ::testing::HasSubstr;

enum class Shape { box, sphere, capsule };

constexpr auto declared_names(const Shape*) {
  return std::array{EnumName{Shape::box, "box", "six faces"}, EnumName{Shape::sphere, "sphere"},
                    EnumName{Shape::capsule, "capsule"}};
}

struct Filter {
  double cutoff = 30.0;
  int order = 2;
};

constexpr auto declared_fields(const Filter*) {
  return declare<Filter>("filter",
                         field("cutoff", &Filter::cutoff, "Hz", Range::positive().or_infinity(),
                               "cut-off frequency; +inf: no filter"),
                         field("order", &Filter::order, "", Range::at_least(1), "filter order"));
}

struct Gains {
  Eigen::Vector3d stiffness{100.0, 100.0, 100.0};
  double damping_ratio = 1.0;
  double blend = 0.5;
  bool enabled = true;
  std::string name = "arm";
  Shape shape = Shape::box;
  Filter filter;
};

constexpr auto declared_fields(const Gains*) {
  using S = Gains;
  return declare<S>("gains",
                    field("stiffness", &S::stiffness, "N/m", Range::positive(), "per axis"),
                    field("damping_ratio", &S::damping_ratio, "", Range::non_negative(), "ζ"),
                    field("blend", &S::blend, "", Range::closed(0.0, 1.0), "mix"),
                    field("enabled", &S::enabled, "on or off"), field("name", &S::name, "label"),
                    field("shape", &S::shape, "geometry"), field("filter", &S::filter, "filter"));
}

std::string check_message(const Gains& g) {
  try {
    check_fields(g);
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Range, SaysWhatItAccepts) {
  EXPECT_EQ(Range::positive().text(), "positive and finite");
  EXPECT_EQ(Range::positive().or_infinity().text(), "positive (+inf allowed)");
  EXPECT_EQ(Range::non_negative().text(), "finite and ≥ 0");
  EXPECT_EQ(Range::at_least(1).text(true), "≥ 1");
  EXPECT_EQ(Range::positive().text(true), "≥ 1");
  EXPECT_EQ(Range::closed(0, 1).text(), "in [0, 1]");
  EXPECT_EQ(Range::open_closed(0, 1).text(), "in (0, 1]");
  EXPECT_EQ(Range::finite().text(), "finite");
}

TEST(Range, RefusesNanAlwaysAndInfinityUnlessAllowed) {
  const double inf = Range::inf;
  EXPECT_FALSE(Range::finite().or_infinity().contains(std::nan("")));
  EXPECT_FALSE(Range::positive().contains(inf));
  EXPECT_TRUE(Range::positive().or_infinity().contains(inf));
  EXPECT_FALSE(Range::positive().or_infinity().contains(-inf));
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_TRUE(Range::non_negative().contains(0.0));
  EXPECT_FALSE(Range::open_closed(0, 1).contains(0.0));
  EXPECT_TRUE(Range::open_closed(0, 1).contains(1.0));
  EXPECT_FALSE(Range::closed(0, 1).contains(1.0 + 1e-12));
}

TEST(CheckFields, AcceptsTheDefaults) { EXPECT_EQ(check_message(Gains{}), "(accepted)"); }

TEST(CheckFields, NamesOwnerPathRangeUnitAndValue) {
  Gains g;
  g.damping_ratio = -0.5;
  EXPECT_EQ(check_message(g), "gains: damping_ratio must be finite and ≥ 0, got -0.5");
  g = Gains{};
  g.stiffness[2] = 0.0;
  EXPECT_EQ(check_message(g), "gains: stiffness[2] must be positive and finite [N/m], got 0");
  g = Gains{};
  g.blend = std::nan("");
  EXPECT_EQ(check_message(g), "gains: blend must be in [0, 1], got nan");
  g = Gains{};
  g.filter.order = 0;
  EXPECT_EQ(check_message(g), "gains: filter.order must be ≥ 1, got 0");
  g = Gains{};
  g.filter.cutoff = Range::inf;
  EXPECT_EQ(check_message(g), "(accepted)");
  g.filter.cutoff = -1.0;
  EXPECT_EQ(check_message(g), "gains: filter.cutoff must be positive (+inf allowed) [Hz], got -1");
  g = Gains{};
  g.shape = static_cast<Shape>(7);
  EXPECT_EQ(check_message(g), "gains: shape holds 7, which names no value");
}

TEST(CheckFields, TakesTheCallersOwnerName) {
  Gains g;
  g.damping_ratio = -1.0;
  try {
    check_fields(g, "controller 'left'");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("controller 'left': damping_ratio must be"));
  }
}

TEST(DeclaredEnum, NamesBothWays) {
  EXPECT_STREQ(to_string(Shape::capsule), "capsule");
  EXPECT_STREQ(to_string(static_cast<Shape>(9)), "?");
  EXPECT_EQ(enum_from_name<Shape>("sphere"), Shape::sphere);
  EXPECT_FALSE(enum_from_name<Shape>("Sphere").has_value());
  EXPECT_EQ(enum_names<Shape>(), (std::vector<std::string>{"box", "sphere", "capsule"}));
  EXPECT_EQ(parse_enum<Shape>("box", "shape"), Shape::box);
  try {
    parse_enum<Shape>("capsul", "shape", "--shape");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "unknown shape 'capsul' in --shape; closest: capsule; shapes: box, sphere, capsule");
  }
}

TEST(FieldsJson, WritesEveryFieldInOrderAndReadsItBack) {
  Gains g;
  g.stiffness = {1.0, 2.0, 3.0};
  g.shape = Shape::sphere;
  g.filter.cutoff = Range::inf;
  g.name = "left";
  const auto j = fields_to_json(g);
  EXPECT_EQ(j.dump(),
            R"({"stiffness":[1.0,2.0,3.0],"damping_ratio":1.0,"blend":0.5,"enabled":true,)"
            R"("name":"left","shape":"sphere","filter":{"cutoff":null,"order":2}})");
  Gains back;
  fields_from_json(nlohmann::json::parse(j.dump()), back, "gains.json");
  EXPECT_EQ(back.stiffness, g.stiffness);
  EXPECT_EQ(back.shape, Shape::sphere);
  EXPECT_EQ(back.filter.cutoff, Range::inf);
  EXPECT_EQ(back.name, "left");
}

std::string read_message(const char* text) {
  Gains g;
  try {
    fields_from_json(nlohmann::json::parse(text), g, "gains.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(FieldsJson, KeepsAbsentFieldsAndRefusesWhatItCannotRead) {
  EXPECT_EQ(read_message(R"({"blend": 0.25})"), "(accepted)");
  EXPECT_EQ(read_message(R"({"blnd": 0.25})"),
            "gains.json: unknown key 'blnd'; closest: blend; keys: stiffness, damping_ratio, "
            "blend, enabled, name, shape, filter");
  EXPECT_EQ(read_message(R"({"filter": {"ordr": 3}})"),
            "gains.json: unknown key 'ordr' in filter; closest: order; keys: cutoff, order");
  EXPECT_EQ(read_message(R"({"blend": "half"})"), "gains.json: blend must be a number, got string");
  EXPECT_EQ(read_message(R"({"filter": {"order": 2.5}})"),
            "gains.json: filter.order must be a whole number, got 2.5");
  EXPECT_EQ(read_message(R"({"stiffness": [1, 2]})"),
            "gains.json: stiffness must have 3 numbers, got 2");
  EXPECT_EQ(read_message(R"({"shape": "cube"})"),
            "unknown shape 'cube' in gains.json; closest: box; shapes: box, sphere, capsule");
  EXPECT_EQ(read_message(R"({"blend": 2})"), "gains.json: blend must be in [0, 1], got 2");
  EXPECT_EQ(read_message(R"({"damping_ratio": null})"),
            "gains.json: damping_ratio must be a number, got null");
  EXPECT_EQ(read_message(R"([1])"), "gains.json: the document must be an object, got [1]");
}

}  // namespace
}  // namespace mjarm::fields_test
