// Checks the Goldfarb–Idnani working-set factorization against its defining identities:
// Jᵀ H J = I, Jᵀ N = [R; 0] with R upper triangular, after additions and drops, and the
// equality-constrained minimizer against a direct KKT solve.

#include "mjarm/qp/active_set_factor.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <vector>

#include "mjarm/error.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm::qp {
namespace {

Eigen::MatrixXd random_matrix(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

Eigen::MatrixXd random_spd(std::mt19937& rng, int n) {
  const Eigen::MatrixXd m = random_matrix(rng, n, n);
  return m.transpose() * m / n + Eigen::MatrixXd::Identity(n, n);
}

// the identities every state of the factor must satisfy for normals N (columns)
void expect_consistent(const ActiveSetFactor& f, const Eigen::MatrixXd& H,
                       const Eigen::MatrixXd& N) {
  const int n = f.size();
  const int q = f.active_count();
  ASSERT_EQ(q, N.cols());
  const Eigen::MatrixXd jhj = f.j().transpose() * H * f.j();
  EXPECT_LT((jhj - Eigen::MatrixXd::Identity(n, n)).norm(), 1e-12);
  const Eigen::MatrixXd jn = f.j().transpose() * N;
  const Eigen::MatrixXd r = f.r().topLeftCorner(q, q).triangularView<Eigen::Upper>();
  EXPECT_LT((jn.topRows(q) - r).norm(), 1e-12);
  if (q < n) {
    EXPECT_LT(jn.bottomRows(n - q).norm(), 1e-12);
  }
}

TEST(ActiveSetFactor, RejectsEmptyProblem) { EXPECT_THROW(ActiveSetFactor(0), Error); }

TEST(ActiveSetFactor, CholeskyAndInverse) {
  std::mt19937 rng(11);
  const Eigen::MatrixXd H = random_spd(rng, 9);
  ActiveSetFactor f(9);
  ASSERT_TRUE(f.factorize(H));
  EXPECT_LT((f.l() * f.l().transpose() - H).norm(), 1e-12);
  EXPECT_LT((f.j().transpose() * f.l() - Eigen::MatrixXd::Identity(9, 9)).norm(), 1e-12);
  EXPECT_EQ(f.active_count(), 0);
}

TEST(ActiveSetFactor, DetectsIndefiniteHessian) {
  ActiveSetFactor f(3);
  Eigen::Matrix3d H = Eigen::Matrix3d::Identity();
  H(2, 2) = -1.0;
  EXPECT_FALSE(f.factorize(H));
  H(2, 2) = 0.0;  // semidefinite is not enough
  EXPECT_FALSE(f.factorize(H));
  EXPECT_FALSE(f.factorized());
}

TEST(ActiveSetFactor, AddDropKeepsIdentities) {
  std::mt19937 rng(5);
  const int n = 8;
  const Eigen::MatrixXd H = random_spd(rng, n);
  const Eigen::MatrixXd all = random_matrix(rng, n, 6);
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(H));
  std::vector<int> cols;
  Eigen::VectorXd d(n);
  auto normals = [&] {
    Eigen::MatrixXd N(n, static_cast<int>(cols.size()));
    for (size_t k = 0; k < cols.size(); ++k) N.col(static_cast<int>(k)) = all.col(cols[k]);
    return N;
  };
  for (int c = 0; c < 6; ++c) {
    f.project(all.col(c), d);
    ASSERT_TRUE(f.add(d, 1e-10));
    cols.push_back(c);
    expect_consistent(f, H, normals());
  }
  // drop from the middle, the front and the back; a pending direction rotates along
  for (int k : {2, 0, 3}) {
    const Eigen::VectorXd v = random_matrix(rng, n, 1);
    f.project(v, d);
    f.drop(k, &d);
    cols.erase(cols.begin() + k);
    expect_consistent(f, H, normals());
    EXPECT_LT((d - f.j().transpose() * v).norm(), 1e-12);
  }
}

TEST(ActiveSetFactor, RejectsDependentNormals) {
  std::mt19937 rng(6);
  const int n = 5;
  const Eigen::MatrixXd H = random_spd(rng, n);
  const Eigen::MatrixXd N = random_matrix(rng, n, 2);
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(H));
  Eigen::VectorXd d(n);
  for (int c = 0; c < 2; ++c) {
    f.project(N.col(c), d);
    ASSERT_TRUE(f.add(d, 1e-10));
  }
  f.project(0.3 * N.col(0) - 1.7 * N.col(1), d);
  EXPECT_FALSE(f.independent(d, 1e-10));
  EXPECT_FALSE(f.add(d, 1e-10));
  EXPECT_EQ(f.active_count(), 2);
  // the dual direction expresses the dependent normal in the working set normals
  Eigen::VectorXd r(n);
  f.dual_direction(d, r);
  EXPECT_NEAR(r[0], 0.3, 1e-12);
  EXPECT_NEAR(r[1], -1.7, 1e-12);
}

TEST(ActiveSetFactor, UnitNormalMatchesDenseProjection) {
  std::mt19937 rng(7);
  const int n = 6;
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(random_spd(rng, n)));
  Eigen::VectorXd d(n), e(n);
  f.project(random_matrix(rng, n, 1), d);
  ASSERT_TRUE(f.add(d, 1e-10));
  for (int j = 0; j < n; ++j) {
    f.project(-Eigen::VectorXd::Unit(n, j), d);
    f.project_unit(j, -1.0, e);
    EXPECT_LT((d - e).norm(), 1e-15);
  }
}

TEST(ActiveSetFactor, SubproblemMatchesKktSolve) {
  std::mt19937 rng(8);
  const int n = 7, q = 4;
  const Eigen::MatrixXd H = random_spd(rng, n);
  const Eigen::MatrixXd N = random_matrix(rng, n, q);
  const Eigen::VectorXd g = random_matrix(rng, n, 1);
  const Eigen::VectorXd b = random_matrix(rng, q, 1);
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(H));
  f.set_linear_term(g);
  Eigen::VectorXd d(n);
  for (int c = 0; c < q; ++c) {
    f.project(N.col(c), d);
    ASSERT_TRUE(f.add(d, 1e-10));
  }
  Eigen::VectorXd x(n), u(n);
  f.solve_subproblem(b, x, u);
  // [H -N; Nᵀ 0] [x; u] = [-g; b]
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + q, n + q);
  kkt.topLeftCorner(n, n) = H;
  kkt.topRightCorner(n, q) = -N;
  kkt.bottomLeftCorner(q, n) = N.transpose();
  Eigen::VectorXd rhs(n + q);
  rhs << -g, b;
  const Eigen::VectorXd sol = test::solve_lu(kkt, rhs);
  EXPECT_LT((x - sol.head(n)).norm(), 1e-11);
  EXPECT_LT((u.head(q) - sol.tail(q)).norm(), 1e-11);
  // after a drop the subproblem still matches (w = Jᵀg is rotated along)
  f.drop(1, nullptr);
  Eigen::MatrixXd N2(n, q - 1);
  N2 << N.col(0), N.col(2), N.col(3);
  Eigen::VectorXd b2(q - 1);
  b2 << b[0], b[2], b[3];
  f.solve_subproblem(b2, x, u);
  EXPECT_LT((N2.transpose() * x - b2).norm(), 1e-11);
  EXPECT_LT((H * x + g - N2 * u.head(q - 1)).norm(), 1e-11);
}

TEST(ActiveSetFactor, AlignedNormalsKeepIdentities) {
  // with H = I, J starts as I: a normal ±e_j projects onto one column of J₂ only, the cases in
  // which the reflection of add() degenerates to nothing (+) or to a sign change (−)
  const int n = 4;
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(H));
  Eigen::MatrixXd N(n, 0);
  Eigen::VectorXd d(n);
  for (const Eigen::VectorXd& v :
       {Eigen::VectorXd(-Eigen::VectorXd::Unit(n, 0)), Eigen::VectorXd(Eigen::VectorXd::Unit(n, 1)),
        Eigen::VectorXd(-Eigen::VectorXd::Unit(n, 3))}) {
    f.project(v, d);
    ASSERT_TRUE(f.add(d, 1e-10));
    N.conservativeResize(n, N.cols() + 1);
    N.col(N.cols() - 1) = v;
    expect_consistent(f, H, N);
    EXPECT_GT(f.r()(N.cols() - 1, N.cols() - 1), 0.0);  // R keeps a positive diagonal
  }
}

TEST(ActiveSetFactor, SubproblemAfterAddAndChangedRhs) {
  // solve_subproblem() reuses R⁻ᵀb where R and b did not change: after an addition, after a
  // change of one right-hand side and after a drop it must still match a direct KKT solve
  std::mt19937 rng(9);
  const int n = 8, q = 5;
  const Eigen::MatrixXd H = random_spd(rng, n);
  const Eigen::MatrixXd N = random_matrix(rng, n, q);
  const Eigen::VectorXd g = random_matrix(rng, n, 1);
  Eigen::VectorXd b = random_matrix(rng, q, 1);
  ActiveSetFactor f(n);
  ASSERT_TRUE(f.factorize(H));
  f.set_linear_term(g);
  Eigen::VectorXd d(n), x(n), u(n);
  auto expect_kkt = [&](const std::vector<int>& cols) {
    const int m = static_cast<int>(cols.size());
    Eigen::MatrixXd Nw(n, m);
    Eigen::VectorXd bw(m);
    for (int k = 0; k < m; ++k) {
      Nw.col(k) = N.col(cols[k]);
      bw[k] = b[cols[k]];
    }
    Eigen::VectorXd bf = Eigen::VectorXd::Zero(n);
    bf.head(m) = bw;
    f.solve_subproblem(bf, x, u);
    EXPECT_LT((Nw.transpose() * x - bw).norm(), 1e-11);
    EXPECT_LT((H * x + g - Nw * u.head(m)).norm(), 1e-11);
  };
  std::vector<int> cols;
  for (int c = 0; c < q; ++c) {
    f.project(N.col(c), d);
    ASSERT_TRUE(f.add(d, 1e-10));
    cols.push_back(c);
    expect_kkt(cols);
  }
  b[2] += 0.5;  // a right-hand side in the middle changes
  expect_kkt(cols);
  expect_kkt(cols);  // and nothing changes
  f.drop(1, nullptr);
  cols.erase(cols.begin() + 1);
  expect_kkt(cols);
  f.reset();
  f.set_linear_term(g);  // w = Jᵀg is not kept across a reset
  cols.clear();
  f.project(N.col(4), d);
  ASSERT_TRUE(f.add(d, 1e-10));
  cols.push_back(4);
  expect_kkt(cols);
}

}  // namespace
}  // namespace mjarm::qp
