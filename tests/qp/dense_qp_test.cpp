// DenseQp: KKT conditions on seeded random problems, a brute-force active-set enumeration on
// tiny ones, degenerate and infeasible problems, the status codes, warm starts and H reuse.

#include "mjarm/qp/dense_qp.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "mjarm/error.hpp"
#include "qp/qp_test_support.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm::qp {
namespace {

using test::gaussian;
using test::kInf;
using test::load;
using test::Problem;

// feasible by construction around a hidden point x0; g pushes the minimizer into the limits
Problem random_problem(std::mt19937& rng, int n, int me, int mi, bool bounds = true) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Problem p;
  const Eigen::MatrixXd M = gaussian(rng, n, n);
  p.H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
  p.g = gaussian(rng, n, 1, 4.0);
  p.x0 = gaussian(rng, n, 1, 0.5);
  const Eigen::VectorXd& x0 = p.x0;
  p.A = gaussian(rng, me, n);
  p.b = p.A * x0;
  p.C = gaussian(rng, mi, n);
  const Eigen::VectorXd cx0 = p.C * x0;
  p.l.resize(mi);
  p.u.resize(mi);
  for (int i = 0; i < mi; ++i) {
    const double kind = uni(rng);
    p.l[i] = kind < 0.2 ? -kInf : cx0[i] - 0.05 - uni(rng);
    p.u[i] = kind > 0.8 ? kInf : cx0[i] + 0.05 + uni(rng);
  }
  p.lb = Eigen::VectorXd::Constant(n, -kInf);
  p.ub = Eigen::VectorXd::Constant(n, kInf);
  if (bounds) {
    for (int j = 0; j < n; ++j) {
      p.lb[j] = x0[j] - 0.1 - uni(rng);
      p.ub[j] = x0[j] + 0.1 + uni(rng);
    }
  }
  return p;
}

// stationarity, primal feasibility, dual sign per side and complementarity, all to `tol`
void expect_kkt(const Problem& p, const QpResult& r, double tol = 1e-9) {
  ASSERT_EQ(r.status, QpStatus::solved);
  const Eigen::VectorXd& x = r.x;
  const Eigen::VectorXd stat =
      p.H * x + p.g + p.A.transpose() * r.y_eq + p.C.transpose() * r.y_in + r.y_bound;
  EXPECT_LT(stat.lpNorm<Eigen::Infinity>(), tol) << "stationarity";
  if (p.A.rows() > 0) {
    EXPECT_LT((p.A * x - p.b).lpNorm<Eigen::Infinity>(), tol) << "equality";
  }
  const Eigen::VectorXd cx = p.C * x;
  auto check_side = [&](double v, double lo, double hi, double y, const char* what) {
    EXPECT_GE(v, lo - tol) << what;
    EXPECT_LE(v, hi + tol) << what;
    // a multiplier sits only on the side that holds with equality
    if (y > 0.0) {
      EXPECT_LT(y * std::abs(hi - v), tol) << what << " upper complementarity";
    }
    if (y < 0.0) {
      EXPECT_LT(-y * std::abs(v - lo), tol) << what << " lower complementarity";
    }
  };
  for (int i = 0; i < p.C.rows(); ++i) check_side(cx[i], p.l[i], p.u[i], r.y_in[i], "row");
  for (int j = 0; j < p.n(); ++j) check_side(x[j], p.lb[j], p.ub[j], r.y_bound[j], "bound");
  EXPECT_LT(r.kkt_residual, tol);
  EXPECT_NEAR(r.objective, 0.5 * x.dot(p.H * x) + p.g.dot(x), 1e-9 * (1 + std::abs(r.objective)));
}

// reference: the best feasible equality-constrained minimizer over all working sets
std::optional<Eigen::VectorXd> brute_force(const Problem& p) {
  const int n = p.n(), me = static_cast<int>(p.A.rows()), mi = static_cast<int>(p.C.rows());
  const int total = mi + n;  // rows then bounds: each free, lower or upper
  int combos = 1;
  for (int k = 0; k < total; ++k) combos *= 3;
  std::optional<Eigen::VectorXd> best;
  double best_f = kInf;
  for (int code = 0; code < combos; ++code) {
    std::vector<Eigen::VectorXd> rows;
    std::vector<double> rhs;
    for (int i = 0; i < me; ++i) {
      rows.push_back(p.A.row(i).transpose());
      rhs.push_back(p.b[i]);
    }
    bool ok = true;
    for (int k = 0, c = code; k < total; ++k, c /= 3) {
      if (c % 3 == 0) continue;
      const double limit =
          k < mi ? (c % 3 == 1 ? p.l[k] : p.u[k]) : (c % 3 == 1 ? p.lb[k - mi] : p.ub[k - mi]);
      if (!std::isfinite(limit)) ok = false;
      rows.push_back(k < mi ? Eigen::VectorXd(p.C.row(k).transpose())
                            : Eigen::VectorXd(Eigen::VectorXd::Unit(n, k - mi)));
      rhs.push_back(limit);
    }
    const int q = static_cast<int>(rows.size());
    if (!ok || q > n) continue;
    Eigen::MatrixXd N(n, q);
    for (int k = 0; k < q; ++k) N.col(k) = rows[k];
    if (q > 0 && test::rank(N) < q) continue;
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + q, n + q);
    kkt.topLeftCorner(n, n) = p.H;
    kkt.topRightCorner(n, q) = N;
    kkt.bottomLeftCorner(q, n) = N.transpose();
    Eigen::VectorXd b(n + q);
    b.head(n) = -p.g;
    for (int k = 0; k < q; ++k) b[n + k] = rhs[k];
    const Eigen::VectorXd x = test::solve_lu(kkt, b).head(n);
    const Eigen::VectorXd cx = p.C * x;
    bool feasible = me == 0 || (p.A * x - p.b).lpNorm<Eigen::Infinity>() < 1e-9;
    for (int i = 0; i < mi; ++i)
      feasible = feasible && cx[i] >= p.l[i] - 1e-9 && cx[i] <= p.u[i] + 1e-9;
    for (int j = 0; j < n; ++j)
      feasible = feasible && x[j] >= p.lb[j] - 1e-9 && x[j] <= p.ub[j] + 1e-9;
    const double f = 0.5 * x.dot(p.H * x) + p.g.dot(x);
    if (feasible && f < best_f) {
      best_f = f;
      best = x;
    }
  }
  return best;
}

TEST(DenseQp, RandomProblemsSatisfyKkt) {
  struct Size {
    int n, me, mi;
  };
  std::mt19937 rng(2024);
  for (const Size s : {Size{2, 0, 3}, Size{5, 1, 10}, Size{7, 0, 42}, Size{10, 3, 25},
                       Size{14, 2, 100}, Size{30, 5, 200}}) {
    DenseQp qp(s.n, s.me, s.mi);
    for (int trial = 0; trial < 10; ++trial) {
      const Problem p = random_problem(rng, s.n, s.me, s.mi, trial % 3 != 2);
      load(qp, p);
      const QpResult& r = qp.solve(QpStart::cold);
      SCOPED_TRACE(testing::Message() << "n " << s.n << " mi " << s.mi << " trial " << trial);
      expect_kkt(p, r);
    }
  }
}

TEST(DenseQp, MatchesBruteForceOnTinyProblems) {
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> nd(1, 3), md(0, 4), med(0, 1);
  int solved = 0, infeasible = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const int n = nd(rng), mi = md(rng), me = std::min(med(rng), n - 1);
    Problem p = random_problem(rng, n, me, mi, trial % 2 == 0);
    if (trial % 5 == 4) {
      // narrow random limits, unrelated to the hidden point: sometimes infeasible
      p.l = gaussian(rng, mi, 1, 2.0);
      p.u = p.l + Eigen::VectorXd::Constant(mi, 0.3);
    }
    DenseQp qp(n, me, mi);
    load(qp, p);
    const QpResult& r = qp.solve();
    const std::optional<Eigen::VectorXd> ref = brute_force(p);
    SCOPED_TRACE(testing::Message() << "trial " << trial);
    if (ref) {
      ++solved;
      expect_kkt(p, r);
      EXPECT_LT((r.x - *ref).lpNorm<Eigen::Infinity>(), 1e-8);
    } else {
      ++infeasible;
      EXPECT_EQ(r.status, QpStatus::infeasible);
    }
  }
  EXPECT_GT(solved, 100);
  EXPECT_GT(infeasible, 0);
}

TEST(DenseQp, UnconstrainedEqualityOnlyBoundOnly) {
  std::mt19937 rng(3);
  const Problem base = random_problem(rng, 6, 0, 0, false);
  {
    DenseQp qp(6, 0, 0);
    load(qp, base);
    const QpResult& r = qp.solve();
    expect_kkt(base, r);
    EXPECT_LT((r.x + test::solve_llt(base.H, base.g)).norm(), 1e-12);
    EXPECT_EQ(r.iterations, 0);
  }
  {
    Problem p = random_problem(rng, 6, 3, 0, false);
    DenseQp qp(6, 3, 0);
    load(qp, p);
    const QpResult& r = qp.solve();
    expect_kkt(p, r);
  }
  {
    // diagonal H with bounds only: the answer is the clamped unconstrained minimizer
    Problem p = base;
    p.H = Eigen::VectorXd::LinSpaced(6, 1.0, 3.0).asDiagonal();
    p.lb = Eigen::VectorXd::Constant(6, -0.5);
    p.ub = Eigen::VectorXd::Constant(6, 0.7);
    DenseQp qp(6, 0, 0);
    load(qp, p);
    const QpResult& r = qp.solve();
    expect_kkt(p, r);
    const Eigen::VectorXd expected =
        (-p.g.cwiseQuotient(p.H.diagonal())).cwiseMax(p.lb).cwiseMin(p.ub);
    EXPECT_LT((r.x - expected).norm(), 1e-12);
    // a general H with bounds only
    Problem q = random_problem(rng, 9, 0, 0, true);
    DenseQp qp2(9, 0, 0);
    load(qp2, q);
    expect_kkt(q, qp2.solve());
  }
}

TEST(DenseQp, EqualityRowsAsTwoSidedAndFixedBounds) {
  std::mt19937 rng(4);
  // l = u on three rows and lb = ub on one variable, all through the feasible point x0
  Problem p = random_problem(rng, 8, 0, 12);
  p.l.head(3) = p.C.topRows(3) * p.x0;
  p.u.head(3) = p.l.head(3);
  p.lb[2] = p.ub[2] = p.x0[2];
  DenseQp qp(8, 0, 12);
  load(qp, p);
  const QpResult& r = qp.solve();
  expect_kkt(p, r);
  EXPECT_NEAR(r.x[2], p.x0[2], 1e-12);
  EXPECT_LT((p.C.topRows(3) * r.x - p.l.head(3)).norm(), 1e-12);
}

TEST(DenseQp, DuplicatedAndScaledRows) {
  std::mt19937 rng(5);
  const Problem p = random_problem(rng, 10, 2, 20);
  DenseQp ref(10, 2, 20);
  load(ref, p);
  const QpResult r0 = ref.solve();
  ASSERT_EQ(r0.status, QpStatus::solved);
  // every row twice (once scaled by 3), the equalities twice as well
  Problem d = p;
  d.A.resize(4, 10);
  d.A << p.A, 2.0 * p.A;
  d.b.resize(4);
  d.b << p.b, 2.0 * p.b;
  d.C.resize(40, 10);
  d.C << p.C, 3.0 * p.C;
  d.l.resize(40);
  d.l << p.l, 3.0 * p.l;
  d.u.resize(40);
  d.u << p.u, 3.0 * p.u;
  DenseQp qp(10, 4, 40);
  load(qp, d);
  const QpResult& r = qp.solve();
  expect_kkt(d, r);
  EXPECT_LT((r.x - r0.x).lpNorm<Eigen::Infinity>(), 1e-9);
}

TEST(DenseQp, RedundantActiveConstraintsAtAVertex) {
  // more active rows than variables: x0 is optimal with positive multipliers on 12 rows
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> uni(0.1, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const int n = 6, mi = 16;
    Problem p = random_problem(rng, n, 0, mi, false);
    const Eigen::VectorXd x0 = gaussian(rng, n, 1);
    const Eigen::VectorXd cx0 = p.C * x0;
    Eigen::VectorXd y = Eigen::VectorXd::Zero(mi);
    for (int i = 0; i < mi; ++i) {
      if (i < 12) {
        p.u[i] = cx0[i];  // active upper sides
        p.l[i] = cx0[i] - 1.0;
        y[i] = uni(rng);
      } else {
        p.l[i] = cx0[i] - 0.5;
        p.u[i] = cx0[i] + 0.5;
      }
    }
    p.g = -p.H * x0 - p.C.transpose() * y;
    DenseQp qp(n, 0, mi);
    load(qp, p);
    const QpResult& r = qp.solve();
    SCOPED_TRACE(trial);
    expect_kkt(p, r);
    EXPECT_LT((r.x - x0).lpNorm<Eigen::Infinity>(), 1e-9);
  }
  // the 2-d corner with three rows through it
  Problem p;
  p.H = Eigen::Matrix2d::Identity();
  p.g = Eigen::Vector2d(-2.0, -2.0);
  p.A.resize(0, 2);
  p.b.resize(0);
  p.C.resize(3, 2);
  p.C << 1, 0, 0, 1, 1, 1;
  p.l = Eigen::Vector3d::Constant(-kInf);
  p.u = Eigen::Vector3d(1.0, 1.0, 2.0);
  p.lb = p.ub = Eigen::Vector2d::Constant(0.0);
  p.lb.setConstant(-kInf);
  p.ub.setConstant(kInf);
  DenseQp qp(2, 0, 3);
  load(qp, p);
  const QpResult& r = qp.solve();
  expect_kkt(p, r);
  EXPECT_LT((r.x - Eigen::Vector2d(1.0, 1.0)).norm(), 1e-12);
}

TEST(DenseQp, DetectsInfeasibility) {
  auto make = [](int n, int me, int mi) {
    Problem p;
    p.H = Eigen::MatrixXd::Identity(n, n);
    p.g = Eigen::VectorXd::Ones(n);
    p.A = Eigen::MatrixXd::Zero(me, n);
    p.b = Eigen::VectorXd::Zero(me);
    p.C = Eigen::MatrixXd::Zero(mi, n);
    p.l = Eigen::VectorXd::Constant(mi, -kInf);
    p.u = Eigen::VectorXd::Constant(mi, kInf);
    p.lb = Eigen::VectorXd::Constant(n, -kInf);
    p.ub = Eigen::VectorXd::Constant(n, kInf);
    return p;
  };
  auto expect_infeasible = [](const Problem& p) {
    DenseQp qp(p.n(), static_cast<int>(p.A.rows()), static_cast<int>(p.C.rows()));
    load(qp, p);
    const QpResult& r = qp.solve();
    EXPECT_EQ(r.status, QpStatus::infeasible);
    EXPECT_LE(r.iterations, 10 * (2 * p.n() + p.A.rows() + p.C.rows()) + 100);
  };
  Problem rows = make(2, 0, 2);  // x1 + x2 >= 2 and x1 + x2 <= 1 as separate rows
  rows.C << 1, 1, 1, 1;
  rows.l[0] = 2.0;
  rows.u[1] = 1.0;
  expect_infeasible(rows);
  Problem vs_bounds = make(3, 0, 1);  // 0 <= x <= 1 but x1 + x2 + x3 >= 4
  vs_bounds.C << 1, 1, 1;
  vs_bounds.l[0] = 4.0;
  vs_bounds.lb.setZero();
  vs_bounds.ub.setOnes();
  expect_infeasible(vs_bounds);
  Problem eqs = make(3, 2, 0);  // x1 + x2 = 1 and 2 x1 + 2 x2 = 3
  eqs.A << 1, 1, 0, 2, 2, 0;
  eqs.b << 1, 3;
  expect_infeasible(eqs);
  Problem eq_bound = make(2, 1, 0);  // x1 = 5 but x1 <= 1
  eq_bound.A << 1, 0;
  eq_bound.b << 5;
  eq_bound.ub[0] = 1.0;
  expect_infeasible(eq_bound);
  Problem zero_row = make(2, 0, 1);  // 0 >= 1
  zero_row.l[0] = 1.0;
  expect_infeasible(zero_row);
  // a larger random problem made contradictory by a pair of opposite rows
  std::mt19937 rng(7);
  Problem big = random_problem(rng, 12, 2, 30);
  const Eigen::VectorXd c = big.C.row(0).transpose();
  big.C.row(1) = -2.0 * c.transpose();
  big.l[0] = 1.0;
  big.u[0] = kInf;
  big.l[1] = -1.0;  // -2 c x >= -1, i.e. c x <= 0.5 < 1
  big.u[1] = kInf;
  expect_infeasible(big);
}

TEST(DenseQp, StatusCodes) {
  std::mt19937 rng(8);
  Problem p = random_problem(rng, 5, 1, 8);
  DenseQp qp(5, 1, 8);
  EXPECT_EQ(qp.solve().status, QpStatus::not_convex);  // H is zero until set
  load(qp, p);
  EXPECT_EQ(qp.solve().status, QpStatus::solved);

  Eigen::MatrixXd H = p.H;
  H(4, 4) = -1.0;
  qp.set_hessian(H);
  EXPECT_EQ(qp.solve().status, QpStatus::not_convex);
  const Eigen::MatrixXd v = gaussian(rng, 5, 4);
  qp.set_hessian(v * v.transpose());  // rank 4: semidefinite
  EXPECT_EQ(qp.solve().status, QpStatus::not_convex);
  qp.set_hessian(p.H);
  EXPECT_EQ(qp.solve().status, QpStatus::solved);

  auto expect_invalid_then_restore = [&](auto&& corrupt) {
    corrupt();
    EXPECT_EQ(qp.solve().status, QpStatus::invalid_input);
    load(qp, p);
    EXPECT_EQ(qp.solve().status, QpStatus::solved);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_then_restore([&] {
    Eigen::VectorXd g = p.g;
    g[2] = nan;
    qp.set_gradient(g);
  });
  expect_invalid_then_restore([&] {
    Eigen::MatrixXd h = p.H;
    h(3, 1) = nan;
    qp.set_hessian(h);
  });
  expect_invalid_then_restore([&] {
    Eigen::MatrixXd c = p.C;
    c(0, 0) = nan;
    qp.set_inequalities(c, p.l, p.u);
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd b = p.b;
    b[0] = kInf;
    qp.set_equality_rhs(b);
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd l = p.l;
    l[1] = nan;
    qp.set_inequality_limits(l, p.u);
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd l = p.u.array() + 1.0;
    qp.set_inequality_limits(l, p.u);
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd l = p.l;
    l[0] = kInf;
    qp.set_inequality_limits(l, Eigen::VectorXd::Constant(8, kInf));
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd lb = p.ub.array() + 0.1;
    qp.set_bounds(lb, p.ub);
  });
  expect_invalid_then_restore([&] {
    Eigen::VectorXd ub = p.ub;
    ub[0] = -kInf;
    qp.set_bounds(p.lb, ub);
  });

  // the iteration limit is reported, not hung on
  qp.settings().max_iterations = 1;
  const QpResult& r = qp.solve(QpStart::cold);
  EXPECT_EQ(r.status, QpStatus::iteration_limit);
  qp.settings().max_iterations = 0;
  EXPECT_EQ(qp.solve(QpStart::cold).status, QpStatus::solved);
  EXPECT_STREQ(to_string(QpStatus::not_convex), "not_convex");
}

TEST(DenseQp, SizeMismatchesThrow) {
  EXPECT_THROW(DenseQp(0, 0, 0), Error);
  EXPECT_THROW(DenseQp(3, -1, 0), Error);
  EXPECT_THROW(DenseQp(3, 0, -2), Error);
  DenseQp qp(3, 1, 2);
  EXPECT_THROW(qp.set_hessian(Eigen::MatrixXd::Identity(2, 2)), Error);
  EXPECT_THROW(qp.set_gradient(Eigen::VectorXd::Zero(4)), Error);
  EXPECT_THROW(qp.set_equalities(Eigen::MatrixXd::Zero(2, 3), Eigen::VectorXd::Zero(2)), Error);
  EXPECT_THROW(qp.set_inequalities(Eigen::MatrixXd::Zero(2, 3), Eigen::VectorXd::Zero(2),
                                   Eigen::VectorXd::Zero(3)),
               Error);
  EXPECT_THROW(qp.set_bounds(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(2)), Error);
}

}  // namespace
}  // namespace mjarm::qp
