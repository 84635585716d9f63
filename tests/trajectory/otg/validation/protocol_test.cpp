#include "mjarm/trajectory/otg/validation/protocol.hpp"

#include <gtest/gtest.h>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

// The seeded batch of the validation protocol with a reduced count (the full count runs as
// `mjarm bench otg --cases 1000000`, docs/trajectory_otg.md). Every calculation succeeds, also
// from starts beyond the limits (for any limits); every result keeps the limits at every phase's
// analytic extrema and reaches its target.
TEST(JerkLimitedValidation, SeededBatchKeepsLimitsAndReachesTargets) {
  OtgValidationOptions options;
  options.cases = 3000;
  options.dofs = 7;
  options.seed = 1;
  options.reference_cases = 10;
  options.reference_steps = 80;
  options.structure_seeds = 8;
  const OtgValidationResult r = run_otg_validation(options);
  EXPECT_EQ(r.check_failures, 0) << r.first_failure;
  EXPECT_LE(r.worst_limit_violation, 1e-9);
  EXPECT_LE(r.worst_target_error, 1e-8);
  EXPECT_LE(r.worst_velocity_target_error, 1e-8);
  EXPECT_LE(r.worst_sync_error, 1e-9);
  EXPECT_EQ(r.velocity_failures, 0) << r.first_velocity_failure;
  EXPECT_EQ(r.position_failures, 0) << r.first_failure;
  EXPECT_GT(r.braking_dofs, 0);
  EXPECT_EQ(r.reference_cases, 10);
  EXPECT_EQ(r.optimality_beaten, 0) << r.first_reference_failure;
  EXPECT_EQ(r.reference_not_within, 0) << r.first_reference_failure;
  EXPECT_EQ(r.blocked_mismatches, 0) << r.first_reference_failure;
  // cases drawn with a blocked interval: no motion inside (grid), a profile just outside its ends
  // (the generator's step 3), confirmed by the grid
  EXPECT_EQ(r.blocked_cases, 2);
  EXPECT_GE(r.blocked_checked, 2);
  EXPECT_EQ(r.blocked_end_failures, 0) << r.first_reference_failure;
  EXPECT_EQ(r.blocked_end_not_confirmed, 0);
  EXPECT_GE(r.sync_reference_cases, 9);
  EXPECT_EQ(r.sync_mismatches, 0) << r.first_reference_failure;
  // the same one-DoF cases through the exhaustive search over the switching structures
  EXPECT_EQ(r.structure_cases, 12);
  EXPECT_EQ(r.structure_not_found, 0) << r.first_structure_failure;
  EXPECT_EQ(r.structure_shorter, 0) << r.first_structure_failure;
  EXPECT_EQ(r.structure_longer, 0) << r.first_structure_failure;
  EXPECT_EQ(r.structure_inside_blocked, 0) << r.first_structure_failure;
  EXPECT_GE(r.structure_blocked_ends, 4);
  EXPECT_GT(r.structure_mean_ms, 0.0);
}

// a stop request (Ctrl-C in `mjarm bench otg`) ends the batch with the figures of the cases done
TEST(JerkLimitedValidation, AStopRequestEndsTheBatchWithTheCasesDone) {
  OtgValidationOptions options;
  options.cases = 100000;
  options.reference_cases = 50;
  int asked = 0;
  options.stop = [&] { return ++asked > 2; };
  const OtgValidationResult r = run_otg_validation(options);
  EXPECT_TRUE(r.interrupted);
  EXPECT_GT(r.cases, 0);
  EXPECT_LT(r.cases, 100000);
  EXPECT_EQ(r.reference_cases, 0);
  EXPECT_GT(r.mean_us, 0.0);
  EXPECT_GE(r.max_us, r.p99_us);
  // stopped before the first case: no figures, no crash
  options.stop = [] { return true; };
  const OtgValidationResult none = run_otg_validation(options);
  EXPECT_TRUE(none.interrupted);
  EXPECT_EQ(none.cases, 0);
  EXPECT_EQ(none.mean_us, 0.0);
}

TEST(JerkLimitedValidation, RejectsBadOptions) {
  OtgValidationOptions options;
  options.cases = 0;
  EXPECT_THROW(run_otg_validation(options), Error);
  options.cases = 1;
  options.brake_share = 1.5;
  EXPECT_THROW(run_otg_validation(options), Error);
  options.brake_share = 0.1;
  options.structure_seeds = -1;
  EXPECT_THROW(run_otg_validation(options), Error);
}

}  // namespace
}  // namespace mjarm
