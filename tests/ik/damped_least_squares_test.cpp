#include "mjarm/ik/damped_least_squares.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "mjarm/error.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm {
namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd M(rows, cols);
  for (int i = 0; i < M.size(); ++i) M.data()[i] = g(rng);
  return M;
}

TEST(DampedLeastSquares, StepEqualsThePrimalRegularisedSolution) {
  // Jᵀ(JJᵀ + λ²I)⁻¹e = (JᵀJ + λ²I)⁻¹Jᵀe for any shape
  std::mt19937 rng(1);
  for (const auto& [m, n] : {std::pair{3, 7}, std::pair{6, 6}, std::pair{6, 4}, std::pair{9, 15}}) {
    DampedLeastSquares dls(m, n);
    const Eigen::MatrixXd J = random_matrix(m, n, rng);
    const Eigen::VectorXd e = random_matrix(m, 1, rng);
    const double lambda_sq = 0.04;
    ASSERT_TRUE(dls.factor(J, lambda_sq));
    Eigen::VectorXd dq(n);
    dls.step(J, e, dq);
    const Eigen::MatrixXd H = J.transpose() * J + lambda_sq * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd expected = test::solve_ldlt(H, J.transpose() * e);
    EXPECT_LT((dq - expected).norm(), 1e-10 * (1 + expected.norm()));
  }
}

TEST(DampedLeastSquares, NullSpaceProjectionWithTinyDamping) {
  std::mt19937 rng(2);
  DampedLeastSquares dls(3, 7);
  const Eigen::MatrixXd J = random_matrix(3, 7, rng);
  ASSERT_TRUE(dls.factor(J, 1e-12));
  const Eigen::VectorXd v = random_matrix(7, 1, rng);
  Eigen::VectorXd out(7);
  dls.project(J, v, out);
  EXPECT_LT((J * out).norm(), 1e-9);  // no task motion
  EXPECT_LT((J * (v - out)).norm() - (J * v).norm(), 1e-12);
  Eigen::VectorXd in_place = v;
  dls.project(J, in_place, in_place);  // aliasing allowed
  EXPECT_LT((in_place - out).norm(), 1e-14);
  // the row-space projector P: symmetric, eigenvalues σ²/(σ² + λ²) in [0, 1], P + N = I
  Eigen::MatrixXd P(7, 7);
  dls.row_space_projector(J, P);
  EXPECT_LT((P - P.transpose()).norm(), 1e-12);
  const Eigen::VectorXd eig = test::symmetric_eigenvalues(P);
  EXPECT_GT(eig.minCoeff(), -1e-12);
  EXPECT_LT(eig.maxCoeff(), 1.0 + 1e-12);
  EXPECT_LT((v - P * v - out).norm(), 1e-12);
}

TEST(DampedLeastSquares, DampingBoundsTheStepAtASingularity) {
  // a rank-1 Jacobian and an error off its range: ‖Δq‖ ≤ ‖e‖ / (2λ)
  DampedLeastSquares dls(2, 2);
  Eigen::MatrixXd J(2, 2);
  J << 1e-9, 0.0, 0.0, 1.0;
  const double lambda = 0.02;
  ASSERT_TRUE(dls.factor(J, lambda * lambda));
  Eigen::VectorXd dq(2);
  dls.step(J, Eigen::Vector2d(1.0, 0.0), dq);
  EXPECT_LE(dq.norm(), 1.0 / (2 * lambda));
}

TEST(DampedLeastSquares, ReportsNonFiniteInputAndBadSizes) {
  DampedLeastSquares dls(3, 4);
  Eigen::MatrixXd J = Eigen::MatrixXd::Ones(3, 4);
  J(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(dls.factor(J, 1e-4));
  EXPECT_THROW(DampedLeastSquares(0, 3), Error);
  EXPECT_THROW(DampedLeastSquares(3, -1), Error);
  EXPECT_EQ(dls.rows(), 3);
  EXPECT_EQ(dls.cols(), 4);
}

}  // namespace
}  // namespace mjarm
