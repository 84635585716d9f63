#include "mjarm/control/adaptive_compliance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "support/error_message.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm {
namespace {

/// A random symmetric positive definite 6×6 with eigenvalues in [lo, lo + s] roughly.
Matrix6d ac_random_spd(std::mt19937_64& rng, double lo, double s) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Matrix6d B = Matrix6d::NullaryExpr([&] { return u(rng); });
  return lo * Matrix6d::Identity() + (s / 6.0) * B * B.transpose();
}

TEST(AdaptiveCompliance, StiffnessScaleFollowsTheSigmoidAndItsClip) {
  AdaptiveComplianceOptions o;
  o.deadband = 2.0;
  o.force_gain = 0.5;
  o.min_stiffness_ratio = 0.3;
  AdaptiveCompliance a(o);
  const Matrix6d I = Matrix6d::Identity();
  // below the deadband: F_eff = 0, α = ½, K_r = K0/2
  a.update((Vector6d() << 1.0, 1.0, 0.0, 0.5, 0.0, 0.0).finished(), I);
  EXPECT_EQ(a.effective_force(), 0.0);
  EXPECT_EQ(a.alpha(), 0.5);
  EXPECT_EQ(a.scale(), 0.5);
  EXPECT_LE((a.stiffness() - 0.5 * o.stiffness).norm(), 1e-12 * o.stiffness.norm());
  // ‖[f; n]‖ = 3 N: F_eff = 1, α = 1/(1 + e^(−0.5)) = 0.6225, s = 0.3775
  a.update((Vector6d() << 0.0, 2.0, 2.0, 1.0, 0.0, 0.0).finished(), I);
  EXPECT_DOUBLE_EQ(a.effective_force(), 1.0);
  EXPECT_NEAR(a.alpha(), 1.0 / (1.0 + std::exp(-0.5)), 1e-15);
  EXPECT_NEAR(a.scale(), 1.0 - 1.0 / (1.0 + std::exp(-0.5)), 1e-15);
  // a large force: clipped at r_min
  a.update(Vector6d::Constant(10.0), I);
  EXPECT_EQ(a.scale(), 0.3);
  EXPECT_LE((a.stiffness() - 0.3 * o.stiffness).norm(), 1e-12 * o.stiffness.norm());
  // a non-finite wrench counts as no force
  a.update(Vector6d::Constant(NAN), I);
  EXPECT_EQ(a.scale(), 0.5);
}

TEST(AdaptiveCompliance, LambdaRootAndReferenceDamping) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    AdaptiveComplianceOptions o;
    o.stiffness = ac_random_spd(rng, 50.0, 2000.0);
    AdaptiveCompliance a(o);
    const Matrix6d Lambda_inv = ac_random_spd(rng, 0.02, 5.0);
    a.update(Vector6d::Constant(trial * 0.4), Lambda_inv);
    // Λ^½: the symmetric positive definite root of Λ = (Λ⁻¹)⁻¹ (unique)
    const Eigen::MatrixXd Lambda = test::inverse(Lambda_inv);
    const Matrix6d& R = a.lambda_sqrt();
    EXPECT_LE((R - R.transpose()).norm(), 1e-12 * R.norm());
    EXPECT_LE((R * R - Lambda).norm(), 1e-10 * Lambda.norm());
    EXPECT_GT(test::symmetric_eigenvalues(R).minCoeff(), 0.0);
    // K0^½ likewise, and D_r = Λ^½·K_r^½ + K_r^½·Λ^½ with K_r^½ = √s·K0^½
    const Matrix6d& S = a.nominal_stiffness_sqrt();
    EXPECT_LE((S * S - o.stiffness).norm(), 1e-10 * o.stiffness.norm());
    const Matrix6d Kr_sqrt = std::sqrt(a.scale()) * S;
    const Matrix6d D = R * Kr_sqrt + Kr_sqrt * R;
    EXPECT_LE((a.damping() - D).norm(), 1e-10 * D.norm());
    EXPECT_LE((a.damping() - a.damping().transpose()).norm(), 1e-12 * D.norm());
    EXPECT_NEAR(a.damping_min_eigenvalue(), test::symmetric_eigenvalues(D).minCoeff(),
                1e-9 * D.norm());
  }
}

TEST(AdaptiveCompliance, IsotropicStiffnessGivesCriticalDamping) {
  // K0 = k·I commutes with Λ: D_r = 2√(s·k)·Λ^½, so D_r² = 4·Λ·K_r — each eigen-direction of Λ
  // closes as λ·ë + 2√(λ·s·k)·ė + s·k·e = 0, ζ = 1
  std::mt19937_64 rng(6);
  AdaptiveComplianceOptions o;
  o.stiffness = 900.0 * Matrix6d::Identity();
  AdaptiveCompliance a(o);
  const Matrix6d Lambda_inv = ac_random_spd(rng, 0.05, 3.0);
  a.update(Vector6d::Zero(), Lambda_inv);
  const Eigen::MatrixXd Lambda = test::inverse(Lambda_inv);
  const Matrix6d D2 = a.damping() * a.damping();
  EXPECT_LE((D2 - 4.0 * Lambda * a.stiffness()).norm(), 1e-9 * D2.norm());
  EXPECT_GT(a.damping_min_eigenvalue(), 0.0);
}

TEST(AdaptiveCompliance, NearSingularLambdaIsFloored) {
  // an eigenvalue of Λ⁻¹ below the floor (1e-3) is raised to it: Λ^½ stays bounded by 1/√floor
  Matrix6d Lambda_inv = Matrix6d::Identity();
  Lambda_inv(2, 2) = 1e-9;
  AdaptiveCompliance a;
  a.update(Vector6d::Zero(), Lambda_inv);
  EXPECT_NEAR(a.lambda_sqrt()(2, 2), 1.0 / std::sqrt(1e-3), 1e-9);
  EXPECT_NEAR(a.lambda_sqrt()(0, 0), 1.0, 1e-12);
  EXPECT_TRUE(a.damping().allFinite());
}

TEST(AdaptiveCompliance, GainsThatAreNotPositiveDefiniteThrow) {
  auto error = [](auto edit) {
    AdaptiveComplianceOptions o;
    edit(o);
    return test::error_of([&] { AdaptiveCompliance a(o); });
  };
  const std::string indefinite = error([](auto& o) { o.stiffness(3, 3) = -1.0; });
  EXPECT_NE(indefinite.find("positive definite"), std::string::npos) << indefinite;
  EXPECT_NE(indefinite.find("eigenvalues"), std::string::npos) << indefinite;
  EXPECT_NE(error([](auto& o) { o.stiffness(5, 5) = 0.0; }).find("positive definite"),
            std::string::npos);
  EXPECT_NE(error([](auto& o) { o.stiffness(0, 1) = 5.0; }).find("symmetric"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.stiffness(2, 2) = NAN; }).find("finite"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.deadband = -1.0; }).find("deadband"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.force_gain = 0.0; }).find("force_gain"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.min_stiffness_ratio = 0.0; }).find("ratio"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.min_stiffness_ratio = 1.5; }).find("ratio"), std::string::npos);
  EXPECT_NE(error([](auto& o) { o.min_eigenvalue = 0.0; }).find("eigenvalue"), std::string::npos);
}

}  // namespace
}  // namespace mjarm
