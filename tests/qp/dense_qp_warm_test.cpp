// DenseQp warm starts: the same answer as a cold start on perturbed problems, in fewer
// iterations; the re-add path after matrix changes; fallbacks; reuse of the Cholesky factor.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "mjarm/qp/dense_qp.hpp"
#include "qp/qp_test_support.hpp"

namespace mjarm::qp {
namespace {

using test::gaussian;
using test::kInf;
using test::load;
using test::Problem;

// feasible around x = 0 (equalities through a point near it); g pushes x into the limits
Problem problem_near_origin(std::mt19937& rng, int n, int me, int mi) {
  std::uniform_real_distribution<double> uni(0.5, 1.5);
  Problem p;
  const Eigen::MatrixXd M = gaussian(rng, n, n);
  p.H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
  p.g = gaussian(rng, n, 1, 3.0);
  p.A = gaussian(rng, me, n);
  p.b = p.A * gaussian(rng, n, 1, 0.1);
  p.C = gaussian(rng, mi, n);
  p.l.resize(mi);
  p.u.resize(mi);
  for (int i = 0; i < mi; ++i) {
    const double norm = p.C.row(i).norm();
    p.l[i] = -1.5 * norm * uni(rng);
    p.u[i] = 1.5 * norm * uni(rng);
  }
  p.lb.resize(n);
  p.ub.resize(n);
  for (int j = 0; j < n; ++j) {
    p.lb[j] = -1.5 * uni(rng);
    p.ub[j] = 1.5 * uni(rng);
  }
  return p;
}

// 1 % additive perturbation of g, b_eq and every limit
Problem perturbed(std::mt19937& rng, const Problem& p) {
  Problem q = p;
  const int n = static_cast<int>(p.g.size());
  const int me = static_cast<int>(p.b.size()), mi = static_cast<int>(p.l.size());
  q.g += 0.03 * gaussian(rng, n, 1);
  q.b += 0.001 * gaussian(rng, me, 1);
  q.l += 0.015 * gaussian(rng, mi, 1);
  q.u += 0.015 * gaussian(rng, mi, 1);
  q.lb += 0.015 * gaussian(rng, n, 1);
  q.ub += 0.015 * gaussian(rng, n, 1);
  return q;
}

double stationarity(const Problem& p, const QpResult& r) {
  return (p.H * r.x + p.g + p.A.transpose() * r.y_eq + p.C.transpose() * r.y_in + r.y_bound)
      .lpNorm<Eigen::Infinity>();
}

TEST(DenseQpWarm, SameAnswerAsColdInFewerIterations) {
  struct Size {
    int n, me, mi;
  };
  std::mt19937 rng(31);
  for (const Size s : {Size{7, 0, 42}, Size{10, 3, 40}, Size{14, 0, 100}, Size{30, 0, 200}}) {
    const Problem base = problem_near_origin(rng, s.n, s.me, s.mi);
    DenseQp warm(s.n, s.me, s.mi), cold(s.n, s.me, s.mi);
    load(warm, base);
    load(cold, base);
    ASSERT_EQ(warm.solve().status, QpStatus::solved);
    long warm_iterations = 0, cold_iterations = 0;
    for (int trial = 0; trial < 20; ++trial) {
      const Problem p = perturbed(rng, base);
      warm.set_gradient(p.g);
      warm.set_equality_rhs(p.b);
      warm.set_inequality_limits(p.l, p.u);
      warm.set_bounds(p.lb, p.ub);
      load(cold, p);
      const QpResult& rw = warm.solve(QpStart::warm);
      const QpResult& rc = cold.solve(QpStart::cold);
      SCOPED_TRACE(testing::Message() << "n " << s.n << " trial " << trial);
      ASSERT_EQ(rw.status, QpStatus::solved);
      ASSERT_EQ(rc.status, QpStatus::solved);
      EXPECT_TRUE(rw.warm_started);
      EXPECT_FALSE(rc.warm_started);
      EXPECT_LT((rw.x - rc.x).lpNorm<Eigen::Infinity>(), 1e-10);
      EXPECT_LT((rw.y_in - rc.y_in).lpNorm<Eigen::Infinity>(), 1e-9);
      EXPECT_LT(stationarity(p, rw), 1e-9);
      EXPECT_LT(rw.kkt_residual, 1e-9);
      warm_iterations += rw.iterations;
      cold_iterations += rc.iterations;
    }
    // the perturbation keeps most of the working set: warm starts need a fraction of the steps
    EXPECT_LT(3 * warm_iterations, cold_iterations) << "n " << s.n;
  }
}

TEST(DenseQpWarm, ReAddsWorkingSetAfterMatrixChanges) {
  std::mt19937 rng(32);
  const Problem base = problem_near_origin(rng, 12, 2, 60);
  DenseQp warm(12, 2, 60), cold(12, 2, 60);
  load(warm, base);
  ASSERT_EQ(warm.solve().status, QpStatus::solved);
  Problem p = base;
  for (int change = 0; change < 3; ++change) {
    // a new H (Cholesky again), new C rows, new A_eq: the factorization is rebuilt by re-adding
    if (change == 0) {
      p.H += 0.01 * Eigen::MatrixXd::Identity(12, 12);
      warm.set_hessian(p.H);
    } else if (change == 1) {
      p.C += 0.01 * gaussian(rng, 60, 12);
      warm.set_inequalities(p.C, p.l, p.u);
    } else {
      p.A += 0.01 * gaussian(rng, 2, 12);
      warm.set_equalities(p.A, p.b);
    }
    load(cold, p);
    const QpResult& rw = warm.solve();
    const QpResult& rc = cold.solve(QpStart::cold);
    ASSERT_EQ(rw.status, QpStatus::solved);
    EXPECT_TRUE(rw.warm_started);
    EXPECT_LT((rw.x - rc.x).lpNorm<Eigen::Infinity>(), 1e-10);
    EXPECT_LT(rw.iterations, rc.iterations);
  }
}

TEST(DenseQpWarm, HandlesRemovedLimitsAndLargeChanges) {
  std::mt19937 rng(33);
  Problem p = problem_near_origin(rng, 9, 1, 30);
  DenseQp warm(9, 1, 30), cold(9, 1, 30);
  load(warm, p);
  const QpResult& r0 = warm.solve();
  ASSERT_EQ(r0.status, QpStatus::solved);
  // every active side of the previous solution is removed
  for (int i = 0; i < 30; ++i) {
    if (r0.y_in[i] > 0.0) p.u[i] = kInf;
    if (r0.y_in[i] < 0.0) p.l[i] = -kInf;
  }
  for (int j = 0; j < 9; ++j) {
    if (r0.y_bound[j] > 0.0) p.ub[j] = kInf;
    if (r0.y_bound[j] < 0.0) p.lb[j] = -kInf;
  }
  warm.set_inequality_limits(p.l, p.u);
  warm.set_bounds(p.lb, p.ub);
  load(cold, p);
  EXPECT_LT((warm.solve().x - cold.solve(QpStart::cold).x).lpNorm<Eigen::Infinity>(), 1e-10);
  // the opposite gradient: most of the old working set is wrong
  p.g = -p.g;
  warm.set_gradient(p.g);
  load(cold, p);
  const QpResult& rw = warm.solve();
  ASSERT_EQ(rw.status, QpStatus::solved);
  EXPECT_LT((rw.x - cold.solve(QpStart::cold).x).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(DenseQpWarm, InfeasibleAfterWarmStartAndRecovery) {
  std::mt19937 rng(34);
  const Problem p = problem_near_origin(rng, 6, 0, 10);
  DenseQp qp(6, 0, 10);
  load(qp, p);
  ASSERT_EQ(qp.solve().status, QpStatus::solved);
  // row 0 pushed beyond what the bounds allow
  Eigen::VectorXd l = p.l, u = p.u;
  l[0] = u[0] = 1e3;
  qp.set_inequality_limits(l, u);
  const QpResult& bad = qp.solve();
  EXPECT_EQ(bad.status, QpStatus::infeasible);
  EXPECT_FALSE(bad.warm_started);  // the warm failure was confirmed by a cold start
  qp.set_inequality_limits(p.l, p.u);
  EXPECT_EQ(qp.solve().status, QpStatus::solved);
}

TEST(DenseQpWarm, LongWarmSequenceStaysExact) {
  // hundreds of warm starts on one factorization (and its periodic rebuilds) lose no accuracy
  std::mt19937 rng(35);
  const Problem base = problem_near_origin(rng, 20, 0, 120);
  DenseQp warm(20, 0, 120), cold(20, 0, 120);
  load(warm, base);
  load(cold, base);
  const Problem a = perturbed(rng, base), b = perturbed(rng, base);
  for (int k = 0; k < 300; ++k) {
    const Problem& p = k % 2 == 0 ? a : b;
    warm.set_gradient(p.g);
    warm.set_inequality_limits(p.l, p.u);
    warm.set_bounds(p.lb, p.ub);
    ASSERT_EQ(warm.solve().status, QpStatus::solved) << k;
  }
  const Problem& last = b;
  load(cold, last);
  EXPECT_LT((warm.result().x - cold.solve(QpStart::cold).x).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_LT(stationarity(last, warm.result()), 1e-9);
}

TEST(DenseQpWarm, CholeskyReusedWhileHessianUnchanged) {
  std::mt19937 rng(36);
  const Problem p = problem_near_origin(rng, 8, 1, 20);
  DenseQp qp(8, 1, 20);
  load(qp, p);
  EXPECT_EQ(qp.hessian_factorizations(), 0);  // factorized lazily by solve()
  qp.solve();
  qp.solve(QpStart::cold);
  qp.set_gradient(-p.g);
  qp.set_inequalities(p.C, p.l, p.u);
  const Eigen::VectorXd x1 = qp.solve().x;
  EXPECT_EQ(qp.hessian_factorizations(), 1);
  // the new factor is really used: scaling H and g together keeps the minimizer
  qp.set_hessian(2.0 * p.H);
  qp.set_gradient(-2.0 * p.g);
  const QpResult& r2 = qp.solve();
  EXPECT_EQ(qp.hessian_factorizations(), 2);
  ASSERT_EQ(r2.status, QpStatus::solved);
  EXPECT_LT((r2.x - x1).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_NEAR(r2.objective, 2.0 * (0.5 * x1.dot(p.H * x1) - p.g.dot(x1)), 1e-9);
}

}  // namespace
}  // namespace mjarm::qp
