// BoxQp against DenseQp (an independent method: dual active set) on seeded random box QPs, with
// the KKT conditions checked here from H, g and the bounds alone.

#include "mjarm/qp/box_qp.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>
#include <cmath>
#include <random>

#include "mjarm/error.hpp"
#include "mjarm/qp/dense_qp.hpp"
#include "qp/qp_test_support.hpp"

namespace mjarm::qp {
namespace {

using test::gaussian;
using test::kInf;

struct BoxProblem {
  Eigen::MatrixXd H;
  Eigen::VectorXd g, lb, ub;
};

// H = Q·diag(λ)·Qᵀ with λ log-spaced over [1, cond] (Q a random orthogonal matrix), times a scale
Eigen::MatrixXd box_random_spd(std::mt19937& rng, int n, double cond) {
  const Eigen::MatrixXd Q =
      Eigen::HouseholderQR<Eigen::MatrixXd>(gaussian(rng, n, n)).householderQ();
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Eigen::VectorXd lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = std::pow(cond, uni(rng));
  Eigen::MatrixXd H = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (H + H.transpose()).eval();
}

// a random problem: bounds around 0 with missing sides, some fixed variables
BoxProblem box_random_problem(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double cond = std::pow(10.0, 6.0 * uni(rng));
  BoxProblem p;
  p.H = box_random_spd(rng, n, cond);
  p.g = gaussian(rng, n, 1, 3.0 * std::pow(10.0, 2.0 * uni(rng) - 1.0));
  p.lb.resize(n);
  p.ub.resize(n);
  for (int j = 0; j < n; ++j) {
    const double r = uni(rng);
    p.lb[j] = uni(rng) < 0.15 ? -kInf : -(0.1 + uni(rng));
    p.ub[j] = uni(rng) < 0.15 ? kInf : 0.1 + uni(rng);
    if (r < 0.05) p.lb[j] = p.ub[j] = 0.5 * (uni(rng) - 0.5);  // fixed
  }
  return p;
}

// a problem with a known solution x* where some bounds are active with zero multiplier
BoxProblem box_degenerate_problem(std::mt19937& rng, int n, Eigen::VectorXd& x_star) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  BoxProblem p;
  p.H = box_random_spd(rng, n, std::pow(10.0, 3.0 * uni(rng)));
  p.lb = Eigen::VectorXd::Constant(n, -1.0);
  p.ub = Eigen::VectorXd::Constant(n, 1.0);
  x_star = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);  // H x* + g + y = 0
  for (int j = 0; j < n; ++j) {
    const double r = uni(rng);
    if (r < 0.3) {
      x_star[j] = 2.0 * uni(rng) - 1.0;  // free
    } else if (r < 0.55) {
      x_star[j] = -1.0;  // at lb, zero multiplier (degenerate)
    } else if (r < 0.8) {
      x_star[j] = 1.0;  // at ub, zero multiplier (degenerate)
    } else {
      x_star[j] = uni(rng) < 0.5 ? -1.0 : 1.0;  // strictly active
      y[j] = x_star[j] * (0.1 + uni(rng));      // ≥ 0 at ub, ≤ 0 at lb
    }
  }
  p.g = -p.H * x_star - y;
  return p;
}

void box_load(BoxQp& box, const BoxProblem& p) {
  box.set_hessian(p.H);
  box.set_gradient(p.g);
  box.set_bounds(p.lb, p.ub);
}

void box_load(DenseQp& dense, const BoxProblem& p) {
  dense.set_hessian(p.H);
  dense.set_gradient(p.g);
  dense.set_bounds(p.lb, p.ub);
}

// KKT conditions from the data alone: feasibility, stationarity on the free variables, the sign of
// the multipliers on the bound ones (tolerances scaled by the gradient's magnitude)
void box_expect_kkt(const BoxProblem& p, const BoxQpResult& r, double tol) {
  const Eigen::VectorXd grad = p.H * r.x + p.g;
  const double scale = 1.0 + p.g.lpNorm<Eigen::Infinity>() +
                       (p.H.cwiseAbs() * r.x.cwiseAbs()).lpNorm<Eigen::Infinity>();
  for (int j = 0; j < p.g.size(); ++j) {
    SCOPED_TRACE(j);
    ASSERT_GE(r.x[j], p.lb[j]);
    ASSERT_LE(r.x[j], p.ub[j]);
    const bool at_lb = r.x[j] == p.lb[j], at_ub = r.x[j] == p.ub[j];
    if (!at_lb) {
      EXPECT_LE(grad[j], tol * scale);  // x_j could still decrease: no descent that way
    }
    if (!at_ub) {
      EXPECT_GE(grad[j], -tol * scale);  // x_j could still increase
    }
    // the returned multiplier: −grad on a bound, 0 when free
    EXPECT_NEAR(r.y_bound[j], at_lb || at_ub ? -grad[j] : 0.0, tol * scale);
  }
  EXPECT_LE(r.kkt_residual, tol * scale);
}

TEST(BoxQp, MatchesDenseQpOnRandomProblems) {
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> size(1, 12);
  int total_active = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    SCOPED_TRACE(trial);
    const int n = size(rng);
    const BoxProblem p = box_random_problem(rng, n);
    BoxQp box(n);
    DenseQp dense(n, 0, 0);
    box_load(box, p);
    box_load(dense, p);
    const BoxQpResult& r = box.solve(QpStart::cold);
    const QpResult& d = dense.solve(QpStart::cold);
    ASSERT_EQ(r.status, QpStatus::solved);
    ASSERT_EQ(d.status, QpStatus::solved);
    const double scale = 1.0 + d.x.lpNorm<Eigen::Infinity>();
    EXPECT_LT((r.x - d.x).lpNorm<Eigen::Infinity>(), 1e-9 * scale);
    EXPECT_NEAR(r.objective, d.objective, 1e-9 * (1.0 + std::abs(d.objective)));
    box_expect_kkt(p, r, 1e-11);
    total_active += r.active_count;
  }
  // the sample exercises the bounds: a good share of variables end at one
  EXPECT_GT(total_active, 3000);
}

TEST(BoxQp, DegenerateBoundsWithZeroMultiplier) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 1000; ++trial) {
    SCOPED_TRACE(trial);
    const int n = 1 + trial % 12;
    Eigen::VectorXd x_star;
    const BoxProblem p = box_degenerate_problem(rng, n, x_star);
    BoxQp box(n);
    box_load(box, p);
    const BoxQpResult& r = box.solve(QpStart::cold);
    ASSERT_EQ(r.status, QpStatus::solved);
    EXPECT_LT((r.x - x_star).lpNorm<Eigen::Infinity>(), 1e-9);
    box_expect_kkt(p, r, 1e-11);
    DenseQp dense(n, 0, 0);
    box_load(dense, p);
    ASSERT_EQ(dense.solve().status, QpStatus::solved);
    EXPECT_LT((r.x - dense.result().x).lpNorm<Eigen::Infinity>(), 1e-9);
  }
}

TEST(BoxQp, AllActiveNoneActiveAndFixed) {
  std::mt19937 rng(11);
  const int n = 7;
  BoxProblem p;
  p.H = box_random_spd(rng, n, 100.0);
  p.lb = Eigen::VectorXd::Constant(n, -0.1);
  p.ub = Eigen::VectorXd::Constant(n, 0.1);
  BoxQp box(n);

  // none active: the unconstrained minimizer lies inside
  p.g = -p.H * Eigen::VectorXd::LinSpaced(n, -0.05, 0.05);
  box_load(box, p);
  const BoxQpResult& r = box.solve(QpStart::cold);
  ASSERT_EQ(r.status, QpStatus::solved);
  EXPECT_EQ(r.active_count, 0);
  EXPECT_LT((r.x - Eigen::VectorXd::LinSpaced(n, -0.05, 0.05)).norm(), 1e-12);
  EXPECT_EQ(r.y_bound, Eigen::VectorXd::Zero(n));

  // all active: the gradient dominates H on every variable, alternately outwards
  for (int j = 0; j < n; ++j) p.g[j] = (j % 2 == 0 ? 1.0 : -1.0) * 1e3;
  box_load(box, p);
  box.solve(QpStart::cold);
  ASSERT_EQ(r.status, QpStatus::solved);
  EXPECT_EQ(r.active_count, n);
  for (int j = 0; j < n; ++j) EXPECT_EQ(r.x[j], j % 2 == 0 ? -0.1 : 0.1);
  box_expect_kkt(p, r, 1e-12);

  // lb == ub on every variable: x is the box point, multipliers of either sign
  p.ub = p.lb;
  box_load(box, p);
  box.solve(QpStart::cold);
  ASSERT_EQ(r.status, QpStatus::solved);
  EXPECT_EQ(r.x, p.lb);
  EXPECT_LT((r.y_bound + p.H * r.x + p.g).norm(), 1e-9);
  EXPECT_EQ(r.kkt_residual, 0.0);

  // one variable, unbounded
  BoxQp one(1);
  one.set_hessian(Eigen::MatrixXd::Constant(1, 1, 4.0));
  one.set_gradient(Eigen::VectorXd::Constant(1, 2.0));
  EXPECT_EQ(one.solve().status, QpStatus::solved);
  EXPECT_DOUBLE_EQ(one.result().x[0], -0.5);
  EXPECT_DOUBLE_EQ(one.result().objective, -0.5);
}

TEST(BoxQp, WarmAndColdAgree) {
  std::mt19937 rng(99);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    const int n = 1 + trial % 12;
    BoxProblem p = box_random_problem(rng, n);
    BoxQp warm(n), cold(n);
    box_load(warm, p);
    ASSERT_EQ(warm.solve().status, QpStatus::solved);
    EXPECT_FALSE(warm.result().warm_started);  // nothing to warm start from yet
    // a sequence of nearby problems, like consecutive control steps
    for (int step = 0; step < 5; ++step) {
      for (int j = 0; j < n; ++j) p.g[j] += 0.3 * normal(rng);
      p.H += 0.05 * box_random_spd(rng, n, 10.0);
      box_load(warm, p);
      box_load(cold, p);
      const BoxQpResult& w = warm.solve(QpStart::warm);
      const BoxQpResult& c = cold.solve(QpStart::cold);
      ASSERT_EQ(w.status, QpStatus::solved);
      ASSERT_EQ(c.status, QpStatus::solved);
      EXPECT_TRUE(w.warm_started);
      EXPECT_LT((w.x - c.x).lpNorm<Eigen::Infinity>(),
                1e-9 * (1.0 + c.x.lpNorm<Eigen::Infinity>()));
      box_expect_kkt(p, w, 1e-11);
    }
  }
}

TEST(BoxQp, WarmStartFromTheAnswerTakesOneIteration) {
  std::mt19937 rng(5);
  const BoxProblem p = box_random_problem(rng, 9);
  BoxQp box(9);
  box_load(box, p);
  ASSERT_EQ(box.solve().status, QpStatus::solved);
  const Eigen::VectorXd x = box.result().x;
  box.set_gradient(p.g);  // same problem again
  EXPECT_EQ(box.solve(QpStart::warm).iterations, 1);
  EXPECT_LT((box.result().x - x).norm(), 1e-12);
  // reset_warm_start: the next solve is cold
  box.reset_warm_start();
  EXPECT_FALSE(box.solve(QpStart::warm).warm_started);
}

TEST(BoxQp, Deterministic) {
  std::mt19937 rng(3);
  const BoxProblem p = box_random_problem(rng, 10);
  BoxQp a(10), b(10);
  box_load(a, p);
  box_load(b, p);
  a.solve();
  b.solve();
  EXPECT_EQ(a.result().x, b.result().x);  // bit for bit
  EXPECT_EQ(a.result().y_bound, b.result().y_bound);
  EXPECT_EQ(a.result().iterations, b.result().iterations);
}

TEST(BoxQp, BadInputStatuses) {
  std::mt19937 rng(17);
  const int n = 4;
  const BoxProblem good = box_random_problem(rng, n);
  auto status_of = [&](const BoxProblem& p) {
    BoxQp box(n);
    box_load(box, p);
    return box.solve().status;
  };
  ASSERT_EQ(status_of(good), QpStatus::solved);
  {
    BoxProblem p = good;
    p.H(2, 1) = std::nan("");
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.H(3, 3) = kInf;
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.g[0] = -kInf;
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.lb[1] = 1.0;
    p.ub[1] = 0.5;  // inverted
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.lb[2] = kInf;
    p.ub[2] = kInf;
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.ub[0] = -kInf;
    p.lb[0] = -kInf;
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;
    p.ub[3] = std::nan("");
    EXPECT_EQ(status_of(p), QpStatus::invalid_input);
  }
  {
    BoxProblem p = good;  // indefinite: one negative eigenvalue
    p.H -= 2.0 * p.H.diagonal().maxCoeff() * Eigen::VectorXd::Unit(n, 1) *
           Eigen::VectorXd::Unit(n, 1).transpose();
    EXPECT_EQ(status_of(p), QpStatus::not_convex);
  }
  {
    BoxProblem p = good;  // singular: a zero row and column
    p.H.row(2).setZero();
    p.H.col(2).setZero();
    EXPECT_EQ(status_of(p), QpStatus::not_convex);
  }
  // indefinite even with the bad direction held at bounds: still reported
  {
    BoxProblem p = good;
    p.H = Eigen::MatrixXd::Identity(n, n);
    p.H(0, 0) = -1.0;
    p.lb[0] = p.ub[0] = 0.0;
    EXPECT_EQ(status_of(p), QpStatus::not_convex);
  }
  // H never set: zero
  BoxQp unset(n);
  EXPECT_EQ(unset.solve().status, QpStatus::not_convex);
  EXPECT_EQ(unset.result().kkt_residual, kInf);
  // bad data then good data: the solver recovers
  BoxQp box(n);
  BoxProblem bad = good;
  bad.g[1] = std::nan("");
  box_load(box, bad);
  EXPECT_EQ(box.solve().status, QpStatus::invalid_input);
  box_load(box, good);
  EXPECT_EQ(box.solve().status, QpStatus::solved);
}

TEST(BoxQp, IterationLimitKeepsAFeasibleIterate) {
  std::mt19937 rng(23);
  const int n = 10;
  BoxProblem p;
  p.H = box_random_spd(rng, n, 1e3);
  p.g = gaussian(rng, n, 1, 100.0);  // far outside: many bounds to add
  p.lb = Eigen::VectorXd::Constant(n, -0.1);
  p.ub = Eigen::VectorXd::Constant(n, 0.1);
  BoxQp box(n);
  box_load(box, p);
  ASSERT_EQ(box.solve(QpStart::cold).status, QpStatus::solved);
  ASSERT_GT(box.result().iterations, 2);
  box.settings().max_iterations = 2;
  const BoxQpResult& r = box.solve(QpStart::cold);
  EXPECT_EQ(r.status, QpStatus::iteration_limit);
  EXPECT_EQ(r.iterations, 2);
  EXPECT_TRUE((r.x.array() >= p.lb.array()).all() && (r.x.array() <= p.ub.array()).all());
  EXPECT_GT(r.kkt_residual, 0.0);
  // a failed solve leaves nothing to warm start from
  box.settings().max_iterations = 0;
  EXPECT_FALSE(box.solve(QpStart::warm).warm_started);
}

TEST(BoxQp, SizeErrorsThrow) {
  EXPECT_THROW(BoxQp(0), Error);
  BoxQp box(3);
  EXPECT_THROW(box.set_hessian(Eigen::MatrixXd::Identity(2, 2)), Error);
  EXPECT_THROW(box.set_gradient(Eigen::VectorXd::Zero(4)), Error);
  EXPECT_THROW(box.set_bounds(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)), Error);
}

}  // namespace
}  // namespace mjarm::qp
