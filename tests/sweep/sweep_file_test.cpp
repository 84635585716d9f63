// Sweep files and plans (mjarm/sweep/): the file read and checked against the scenario's
// parameters (every refusal with its place), the grid expanded point-major with zipped axes and
// seeds, the Latin hypercube stratified and seeded, and the plan's hash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

#include "mjarm/error.hpp"
#include "mjarm/sweep/sweep_plan.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

using Json = nlohmann::ordered_json;
using test::error_of;
using ::testing::HasSubstr;

std::string refusal(const std::string& text) {
  return error_of([&] { parse_sweep_file(text, "s.yaml"); });
}

TEST(SweepFile, ReadsTheAxesRangesZipAndSeeds) {
  const SweepFile f = parse_sweep_file(R"(
scenario: pick-place
parameters: {robot: arm6, mode: torque}
axes:
  grasp: [weld, friction]
  object_size: {from: 0.01, to: 0.04, num: 3, log: true}
  noslip: {from: 0, to: 10, num: 3}
  motion.dwell-time: [0.2, 0.4]
zip: [[grasp, motion.dwell-time]]
seeds: {first: 100, count: 3}
record: failures
)",
                                       "s.yaml");
  EXPECT_EQ(f.scenario, "pick-place");
  EXPECT_EQ(f.parameters["mode"], "torque");
  ASSERT_EQ(f.axes.size(), 4u);
  EXPECT_EQ(f.axes[1].name, "object-size");  // as the command line writes it
  EXPECT_EQ(f.axes[1].values.front(), 0.01);
  EXPECT_EQ(f.axes[1].values.back(), 0.04);
  EXPECT_NEAR(f.axes[1].values[1].get<double>(), 0.02, 1e-15);  // log: the geometric middle
  EXPECT_EQ(f.axes[2].values[1], 5);                            // an integer parameter
  ASSERT_EQ(f.groups.size(), 3u);  // grasp+dwell zipped, object-size, noslip
  EXPECT_EQ(f.groups[0], (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(f.first_seed, 100u);
  EXPECT_EQ(f.seeds, 3);
  EXPECT_EQ(f.record, RecordTrials::failures);
}

TEST(SweepFile, JsonAndQuotedScalarsAreReadAsWritten) {
  const SweepFile f = parse_sweep_file(
      R"({"scenario": "shelf-pick", "axes": {"controller": ["ct", "osc"]}})", "s.json");
  EXPECT_EQ(f.axes[0].values[1], "osc");
  EXPECT_THAT(refusal("scenario: shelf-pick\nparameters: {criteria.tolerance: '0.001'}\n"),
              HasSubstr("criteria.tolerance must be a number, got string"));
}

TEST(SweepFile, RefusesWhatItCannotRunNamingThePlace) {
  EXPECT_THAT(refusal("scenario: pick-place\naxis: {grasp: [weld]}\n"),
              HasSubstr("s.yaml: unknown key 'axis'; closest: axes"));
  EXPECT_THAT(refusal("scenario: pick-plce\n"),
              HasSubstr("s.yaml: scenario: unknown scenario 'pick-plce'; closest: pick-place"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {objct-size: [0.02]}\n"),
              HasSubstr("axes.objct-size: unknown parameter 'objct-size'; closest: object-size"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {object-size: [0.02, 0.5]}\n"),
              HasSubstr("axes.object-size[1]: pick-place: object_size must be in [0.005, 0.05]"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {grasp: []}\n"),
              HasSubstr("axes.grasp: an axis needs at least one value"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {grasp: {from: 0, to: 1, num: 2}}\n"),
              HasSubstr("a range needs a number parameter; grasp is name"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {object-size: {from: 0, to: 0.02, num: 3, "
                      "log: true}}\n"),
              HasSubstr("a log range needs from and to > 0"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {grasp: [weld, friction], noslip: [1, 2, 3]}\n"
                      "zip: [[grasp, noslip]]\n"),
              HasSubstr("zipped axes need the same number of values: grasp has 2, noslip 3"));
  EXPECT_THAT(refusal("scenario: pick-place\nparameters: {grasp: weld}\naxes: {grasp: [weld]}\n"),
              HasSubstr("axes.grasp: grasp is set twice"));
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {seed: [1, 2]}\n"),
              HasSubstr("the seed is set by 'seeds:'"));
  EXPECT_THAT(refusal("scenario: docking\nseeds: 3\n"),
              HasSubstr("docking draws nothing (no seed parameter): one trial per point"));
  EXPECT_THAT(refusal("scenario: pick-place\nseeds: 0\n"),
              HasSubstr("seeds: must be a whole number ≥ 1"));
  EXPECT_THAT(refusal("scenario: pick-place\nrecord: some\n"),
              HasSubstr("record: unknown choice 'some'"));
  // 10¹² trials: refused with the count before anything is expanded or run
  EXPECT_THAT(refusal("scenario: pick-place\naxes: {object-size: {from: 0.01, to: 0.02, num: "
                      "1000000}, grasp-force: {from: 1, to: 10, num: 1000}}\nseeds: 1000\n"),
              HasSubstr("the sweep has 1000000000000 trials; at most 100000000"));
  EXPECT_THAT(refusal(""), HasSubstr("s.yaml: the sweep file is empty"));
  EXPECT_THAT(refusal("scenario: [pick"), HasSubstr("not valid YAML or JSON"));
}

SweepPlan plan_of(const std::string& text, std::int64_t shard_size = 4) {
  return make_sweep_plan(parse_sweep_file(text, "s.yaml"), shard_size);
}

TEST(SweepPlan, TrialsArePointMajorWithTheLastAxisFastestAndZippedAxesTogether) {
  const SweepPlan p = plan_of(R"(
scenario: pick-place
parameters: {mode: torque}
axes:
  grasp: [weld, friction]
  noslip: [0, 10, 20]
  motion.dwell-time: [0.2, 0.4]
zip: [[grasp, motion.dwell-time]]
seeds: {first: 7, count: 2}
)");
  EXPECT_EQ(p.points, 6);
  EXPECT_EQ(p.trials, 12);
  EXPECT_EQ(p.shards(), 3);
  EXPECT_EQ(p.shard(2).first, 8);
  EXPECT_EQ(p.shard(2).count, 4);
  const Json t0 = trial_values(p, 0), t1 = trial_values(p, 1), t2 = trial_values(p, 2),
             t11 = trial_values(p, 11);
  EXPECT_EQ(t0["mode"], "torque");
  EXPECT_EQ(t0["seed"], 7);
  EXPECT_EQ(t1["seed"], 8);  // the seeds of a point are neighbours
  EXPECT_EQ(t1["noslip"], t0["noslip"]);
  EXPECT_EQ(t2["noslip"], 10);  // then the last group moves
  EXPECT_EQ(t11["grasp"], "friction");
  EXPECT_EQ(t11["motion.dwell-time"], 0.4);  // zipped with grasp
  EXPECT_EQ(t11["noslip"], 20);
  EXPECT_EQ(trial_point(p, 11), 5);
  std::set<std::string> points;
  for (std::int64_t t = 0; t < p.trials; t += 2) points.insert(trial_values(p, t).dump());
  EXPECT_EQ(points.size(), 6u);  // every point once
}

TEST(SweepPlan, TheLatinHypercubeHasOneSampleInEveryStratumOfEveryRange) {
  const std::string text = R"(
scenario: pick-place
random:
  samples: 10
  seed: 3
  ranges:
    grasp-force: {from: 2, to: 12}
    impratio: {from: 1, to: 100, log: true}
    noslip: {from: 0, to: 50}
)";
  const SweepPlan p = plan_of(text);
  EXPECT_EQ(p.points, 10);
  std::set<int> force_strata, ratio_strata;
  for (std::int64_t t = 0; t < p.trials; ++t) {
    const Json v = trial_values(p, t);
    const double f = v["grasp-force"].get<double>(), r = v["impratio"].get<double>();
    ASSERT_TRUE(f >= 2 && f < 12 && r >= 1 && r < 100) << v.dump();
    EXPECT_TRUE(v["noslip"].is_number_integer());
    force_strata.insert(static_cast<int>((f - 2) / 1.0));
    ratio_strata.insert(static_cast<int>(std::log10(r) / 0.2));
  }
  EXPECT_EQ(force_strata.size(), 10u);
  EXPECT_EQ(ratio_strata.size(), 10u);
  EXPECT_EQ(plan_of(text).samples, p.samples);  // same seed, same design
  std::string other = text;
  other.replace(other.find("seed: 3"), 7, "seed: 4");
  EXPECT_NE(plan_of(other).samples, p.samples);
}

TEST(SweepPlan, TheHashCoversTheSweepAndAFrozenPlanIsCheckedAgainstIt) {
  const std::string text = "scenario: shelf-pick\naxes: {controller: [ct, osc]}\nseeds: 4\n";
  const SweepPlan p = plan_of(text);
  EXPECT_EQ(p.hash.size(), 16u);
  EXPECT_EQ(plan_of(text).hash, p.hash);
  EXPECT_NE(plan_of(text, 3).hash, p.hash);
  EXPECT_NE(plan_of("scenario: shelf-pick\naxes: {controller: [ct, osc]}\nseeds: 5\n").hash,
            p.hash);
  const SweepPlan back = sweep_plan_from_json(sweep_plan_json(p), "plan.json");
  EXPECT_EQ(back.hash, p.hash);
  EXPECT_EQ(trial_values(back, 5), trial_values(p, 5));
  Json edited = sweep_plan_json(p);
  edited["sweep"]["seeds"]["count"] = 40;
  EXPECT_THAT(error_of([&] { sweep_plan_from_json(edited, "plan.json"); }),
              HasSubstr("plan.json: the plan's hash " + p.hash + " does not match its content"));
  EXPECT_EQ(text_hash(""), "cbf29ce484222325");  // FNV-1a's offset basis: the same everywhere
}

TEST(SweepFile, TheExampleSweepsAreValidAndAsLargeAsTheySay) {
  const std::filesystem::path dir =
      std::filesystem::path(MJARM_MODELS_DIR) / ".." / "examples" / "sweeps";
  const std::map<std::string, std::int64_t> trials{
      {"shelf_pick.yaml", 240},   {"pick_place.yaml", 160}, {"docking.yaml", 150},
      {"bimanual_lift.yaml", 30}, {"plan.yaml", 60},        {"pick_place_random.yaml", 200},
      {"wiping.yaml", 120}};
  std::size_t seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml") continue;  // a waypoint file they use
    ASSERT_TRUE(trials.count(name)) << name << " is not listed here";
    EXPECT_EQ(make_sweep_plan(read_sweep_file(entry.path()), 1).trials, trials.at(name)) << name;
    ++seen;
  }
  EXPECT_EQ(seen, trials.size());
}

}  // namespace
}  // namespace mjarm
