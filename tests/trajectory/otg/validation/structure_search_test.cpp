#include "mjarm/trajectory/otg/validation/structure_search.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/random.hpp"
#include "mjarm/trajectory/otg/brake.hpp"
#include "mjarm/trajectory/otg/generator.hpp"
#include "mjarm/trajectory/otg/min_time.hpp"
#include "trajectory/otg/cases.hpp"

// The exhaustive search over the switching structures: the enumeration, textbook minimum
// durations, and the cross-check with the generator's step 1 on seeded cases (a small count; the
// full count runs in `mjarm bench otg`, docs/trajectory_otg.md).

namespace mjarm {
namespace {

bool near_duration(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, b); }

TEST(JerkLimitedStructures, EnumerationKeepsOnlyAdmissibleSequences) {
  const std::vector<SwitchingStructure>& all = switching_structures();
  EXPECT_EQ(all.size(), 678u);
  std::set<std::string> names;
  int previous_size = 0;
  for (const SwitchingStructure& s : all) {
    ASSERT_GE(s.size, 1);
    ASSERT_LE(s.size, SwitchingStructure::kMaxPhases);
    EXPECT_GE(s.size, previous_size) << "shortest first";
    previous_size = s.size;
    names.insert(s.name());
    for (int i = 1; i < s.size; ++i) {
      const JerkArc a = s.arcs[static_cast<std::size_t>(i - 1)];
      const JerkArc b = s.arcs[static_cast<std::size_t>(i)];
      EXPECT_NE(a, b) << s.name();
      EXPECT_FALSE(is_limit_arc(a) && is_limit_arc(b)) << s.name();
      // a cruise at +v_max is entered and left by jerk down; a hold at +a_max entered by jerk up
      if (b == JerkArc::cruise_up || b == JerkArc::hold_down) {
        EXPECT_EQ(a, JerkArc::down) << s.name();
      }
      if (a == JerkArc::cruise_up || a == JerkArc::hold_up) {
        EXPECT_EQ(b, JerkArc::down) << s.name();
      }
      if (b == JerkArc::cruise_down || b == JerkArc::hold_up) {
        EXPECT_EQ(a, JerkArc::up) << s.name();
      }
      if (a == JerkArc::cruise_down || a == JerkArc::hold_down) {
        EXPECT_EQ(b, JerkArc::up) << s.name();
      }
    }
  }
  EXPECT_EQ(names.size(), all.size()) << "names are unique";
  // the textbook seven-phase profile is one of them
  EXPECT_EQ(names.count("+ A+ − V+ − A− +"), 1u);
}

// Rest to rest, textbook closed forms (not the generator's): all three limits reached,
// T = d/v + v/a + a/j; only the jerk limit reached, T = 4·∛(d / 2j).
// From beyond the velocity limit a brake's release (jerk towards the limit) may run straight
// into a cruise on that limit: the braking enumeration adds exactly those sequences.
TEST(JerkLimitedStructures, BrakingEnumerationAddsACruiseAfterTheRelease) {
  const std::vector<SwitchingStructure>& all = switching_structures();
  const std::vector<SwitchingStructure>& braking = braking_switching_structures();
  EXPECT_GT(braking.size(), all.size());
  std::set<std::string> names_all, names_braking;
  for (const SwitchingStructure& s : all) names_all.insert(s.name());
  for (const SwitchingStructure& s : braking) names_braking.insert(s.name());
  EXPECT_EQ(names_braking.count("+ A+ − V− + A+ −"), 1u);
  EXPECT_EQ(names_all.count("+ A+ − V− + A+ −"), 0u);
  for (const std::string& name : names_all) EXPECT_EQ(names_braking.count(name), 1u) << name;
  // the added ones each hold a release followed by a cruise on its side
  for (const std::string& name : names_braking)
    if (names_all.count(name) == 0)
      EXPECT_TRUE(name.find("+ V+") != std::string::npos || name.find("− V−") != std::string::npos)
          << name;
}

// A start beyond the limits is searched over the brake's ends: the shortest motion is the
// generator's (its brake chosen for the whole motion), also where the brake ends in a cruise.
TEST(JerkLimitedStructureSearch, SearchesTheBrakesEndFromBeyondTheLimits) {
  const JerkLimits l{0.93065177329448479, 0.59588715772050138, 24.223010201097495};
  const KinematicState s{2.1046360185479402, -1.4142738639755592, 0.4537810331639141};
  const KinematicState t{-0.0018366082700844721, -0.75629058949630079, 0.47760799995267045};
  JerkLimitedGenerator otg(std::vector<JerkLimits>{l});
  const OtgResult g = otg.calculate(std::vector<KinematicState>{s}, std::vector<KinematicState>{t});
  ASSERT_EQ(g.status, OtgStatus::working);
  const StructureSearchResult r = structure_search_min_time(s, t, l, {8, 3});
  ASSERT_EQ(r.status, StructureSearchStatus::found);
  EXPECT_TRUE(near_duration(r.duration, g.duration)) << r.duration << " " << g.duration;
  EXPECT_EQ(r.best.structure.name(), "+ A+ − V− + A+ −");
}

TEST(JerkLimitedStructureSearch, FindsTextbookRestToRestDurations) {
  const JerkLimits l{1.0, 2.0, 10.0};
  const StructureSearchResult full = structure_search_min_time({0, 0, 0}, {5.0, 0, 0}, l, {8, 0});
  ASSERT_EQ(full.status, StructureSearchStatus::found);
  EXPECT_NEAR(full.duration, 5.0 / 1.0 + 1.0 / 2.0 + 2.0 / 10.0, 1e-9);
  EXPECT_EQ(full.best.structure.name(), "+ A+ − V+ − A− +");
  const StructureSearchResult small =
      structure_search_min_time({1.0, 0, 0}, {1.02, 0, 0}, l, {8, 0});
  ASSERT_EQ(small.status, StructureSearchStatus::found);
  EXPECT_NEAR(small.duration, 4.0 * std::cbrt(0.02 / (2.0 * 10.0)), 1e-9);
  // already there: no phase
  const StructureSearchResult none =
      structure_search_min_time({0.5, 0.2, 0}, {0.5, 0.2, 0}, l, {8, 0});
  ASSERT_EQ(none.status, StructureSearchStatus::found);
  EXPECT_EQ(none.duration, 0.0);
  EXPECT_EQ(none.best.structure.size, 0);
}

// Every reported solution is a motion: integrated on its own it ends on the target.
TEST(JerkLimitedStructureSearch, SolutionsReachTheTarget) {
  test::JerkCaseGenerator cases(21);
  for (int k = 0; k < 3; ++k) {
    const test::JerkCase c = cases.next();
    const StructureSearchResult r = structure_search_min_time(c.start, c.target, c.limits, {8, 1});
    ASSERT_EQ(r.status, StructureSearchStatus::found);
    const KinematicState e = structure_end(c.start, c.limits, r.best);
    EXPECT_NEAR(e.p, c.target.p, 1e-8);
    EXPECT_NEAR(e.v, c.target.v, 1e-8);
    EXPECT_NEAR(e.a, c.target.a, 1e-8);
    double sum = 0.0;
    for (int i = 0; i < r.best.structure.size; ++i) {
      EXPECT_GE(r.best.durations[static_cast<std::size_t>(i)], 0.0);
      sum += r.best.durations[static_cast<std::size_t>(i)];
    }
    EXPECT_NEAR(sum, r.duration, 1e-12 * std::max(1.0, sum));
    EXPECT_FALSE(r.durations.empty());
    // distinct durations are kept 1e-10 relative apart
    EXPECT_NEAR(r.durations.front(), r.duration, 1e-10 * std::max(1.0, r.duration));
    EXPECT_LE(r.feasible_durations.front(), r.duration * (1.0 + 1e-10));
    EXPECT_GT(r.structures_tried, 0);
    EXPECT_GT(r.structures_solved, 0);
  }
}

// The two methods agree: the search's shortest motion is the generator's t_min; every blocked
// interval's ends are extremal motions the search finds and no motion it finds lies inside one.
void expect_agreement(const KinematicState& s, const KinematicState& t, const JerkLimits& l,
                      int seeds) {
  JerkBlock block;
  ASSERT_TRUE(min_time_profile(s, t, l, block));
  const StructureSearchResult r = structure_search_min_time(s, t, l, {seeds, 3});
  ASSERT_EQ(r.status, StructureSearchStatus::found);
  EXPECT_TRUE(near_duration(r.duration, block.t_min))
      << "search " << r.duration << " (" << r.best.structure.name() << "), generator "
      << block.t_min;
  for (int k = 0; k < block.blocked_count; ++k) {
    const JerkInterval in = block.blocked[static_cast<std::size_t>(k)];
    for (const double end : {in.lower, in.upper})
      EXPECT_TRUE(std::any_of(r.durations.begin(), r.durations.end(),
                              [&](double d) { return near_duration(d, end); }))
          << "blocked interval end " << end << " not found";
    for (const double d : r.feasible_durations)
      EXPECT_FALSE(d > in.lower * (1 + 1e-9) && d < in.upper * (1 - 1e-9))
          << "a motion of " << d << " s inside (" << in.lower << ", " << in.upper << ")";
  }
}

TEST(JerkLimitedStructureSearch, AgreesWithTheGeneratorOnRandomCases) {
  test::JerkCaseGenerator cases(3);
  for (int k = 0; k < 4; ++k) {
    const test::JerkCase c = cases.next();
    expect_agreement(c.start, c.target, c.limits, 8);
  }
}

// After a brake (a start beyond the limits), from the state the brake ends in.
TEST(JerkLimitedStructureSearch, AgreesWithTheGeneratorAfterABrake) {
  test::JerkCaseGenerator cases(5);
  const auto u = [](mjarm::Random& r) { return mjarm::uniform(r, -1.0, 1.0); };
  const test::JerkCase c = cases.next();
  KinematicState s;
  do
    s = {0.5, 1.6 * c.limits.velocity * u(cases.rng()),
         1.6 * c.limits.acceleration * u(cases.rng())};
  while (is_startable(s, c.limits));
  JerkProfile brake;
  brake.reset(s);
  ASSERT_TRUE(append_brake(s, c.limits, brake));
  expect_agreement(brake.end(), c.target, c.limits, 8);
}

// A case with a blocked interval (about 1 % of random draws): its ends are found.
TEST(JerkLimitedStructureSearch, ConfirmsABlockedInterval) {
  test::JerkCaseGenerator cases(12);
  JerkBlock block;
  test::JerkCase c = cases.next();
  for (int draw = 0; draw < 100000; ++draw, c = cases.next())
    if (min_time_profile(c.start, c.target, c.limits, block) && block.blocked_count > 0) break;
  ASSERT_GT(block.blocked_count, 0);
  expect_agreement(c.start, c.target, c.limits, 32);
}

// A start a hair inside −v_max accelerating, then a long cruise at +v_max: the case that needed
// the limit arcs restarted on their limit (an error before a 434 s cruise grew along it).
TEST(JerkLimitedStructureSearch, LongCruiseAfterAReversal) {
  const JerkLimits l{0.54758255577242732, 6.8605264380124593, 0.73984115740964518};
  expect_agreement({-237.2503648881424, -0.54758255571766767, 0.90013789143607115},
                   {0.98382933878468215, 0, 0}, l, 8);
}

// A target beyond the limits has no motion: an honest status, no duration.
TEST(JerkLimitedStructureSearch, ReportsNoSolutionForATargetBeyondTheLimits) {
  const StructureSearchResult r =
      structure_search_min_time({0, 0, 0}, {1.0, 2.0, 0}, {1.0, 1.0, 1.0}, {4, 0});
  EXPECT_EQ(r.status, StructureSearchStatus::no_solution);
  EXPECT_TRUE(r.durations.empty());
  EXPECT_TRUE(r.feasible_durations.empty());
}

TEST(JerkLimitedStructureSearch, RejectsBadInput) {
  const KinematicState rest;
  const KinematicState there{1.0, 0.0, 0.0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const JerkLimits& l : {JerkLimits{0.0, 1.0, 1.0}, JerkLimits{1.0, -1.0, 1.0},
                              JerkLimits{1.0, 1.0, nan}, JerkLimits{inf, 1.0, 1.0}})
    EXPECT_THROW(structure_search_min_time(rest, there, l), Error);
  EXPECT_THROW(structure_search_min_time({nan, 0, 0}, there, {}), Error);
  EXPECT_THROW(structure_search_min_time(rest, {1.0, inf, 0}, {}), Error);
  EXPECT_THROW(structure_search_min_time(rest, there, {}, {0, 0}), Error);
}

}  // namespace
}  // namespace mjarm
