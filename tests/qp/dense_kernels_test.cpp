// The dense kernels against plain reference loops, on sizes that hit every tail of the vector
// code, for both the portable and (where the CPU has it) the AVX2/FMA implementation; and one
// QP solved with each, which must agree.

#include "qp/dense_kernels.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "mjarm/qp/dense_qp.hpp"

namespace mjarm::qp {
namespace {

// runs body once per available implementation
template <class F>
void for_each_path(F&& body) {
  for (const bool portable : {true, false}) {
    kernels::force_portable(portable);
    SCOPED_TRACE(portable ? "portable" : "best");
    body();
  }
  kernels::force_portable(false);
}

std::vector<double> random_vector(std::mt19937& rng, int size) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> v(size);
  for (double& e : v) e = normal(rng);
  return v;
}

TEST(DenseKernels, MatchReferenceLoops) {
  std::mt19937 rng(51);
  for_each_path([&] {
    for (const int rows : {0, 1, 3, 4, 5, 7, 15, 16, 17, 30, 33}) {
      for (const int cols : {0, 1, 2, 3, 4, 6, 8, 9, 30}) {
        const int lda = rows + 3;  // a leading dimension larger than the data
        const std::vector<double> A = random_vector(rng, lda * (rows + cols + 2));
        const std::vector<double> x = random_vector(rng, cols + rows + 1);
        SCOPED_TRACE(testing::Message() << rows << "x" << cols);
        // row_dots: rows of `cols` entries spaced lda apart
        std::vector<double> out(rows + 1, 7.0);
        kernels::row_dots(A.data(), rows, cols, lda, x.data(), out.data());
        for (int i = 0; i < rows; ++i) {
          double ref = 0.0;
          for (int k = 0; k < cols; ++k) ref += A[i * lda + k] * x[k];
          EXPECT_NEAR(out[i], ref, 1e-13);
        }
        EXPECT_EQ(out[rows], 7.0);  // nothing written past the end
        // columns_times: y = A x for column-major A
        std::vector<double> y(rows + 1, 7.0);
        kernels::columns_times(A.data(), rows, cols, lda, x.data(), y.data());
        for (int i = 0; i < rows; ++i) {
          double ref = 0.0;
          for (int k = 0; k < cols; ++k) ref += A[k * lda + i] * x[k];
          EXPECT_NEAR(y[i], ref, 1e-13);
        }
        EXPECT_EQ(y[rows], 7.0);
        // dot and axpy
        double ref = 0.0;
        for (int k = 0; k < cols; ++k) ref += A[k] * x[k];
        EXPECT_NEAR(kernels::dot(A.data(), x.data(), cols), ref, 1e-13);
        std::vector<double> z(x.begin(), x.end());
        kernels::axpy(0.5, A.data(), z.data(), cols);
        for (int k = 0; k < cols; ++k) EXPECT_NEAR(z[k], x[k] + 0.5 * A[k], 1e-15);
        for (int k = cols; k < static_cast<int>(z.size()); ++k) EXPECT_EQ(z[k], x[k]);
      }
    }
  });
}

TEST(DenseKernels, RotationChainsMatchSingleRotations) {
  std::mt19937 rng(52);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for_each_path([&] {
    for (const int rows : {1, 4, 6, 30}) {
      for (const bool descending : {true, false}) {
        const int n = 9, first = 2, count = 5;
        const std::vector<double> start = random_vector(rng, rows * n);
        std::vector<double> c(count), s(count);
        for (int t = 0; t < count; ++t) {
          const double a = angle(rng);
          c[t] = std::cos(a);
          s[t] = std::sin(a);
        }
        std::vector<double> chain = start, single = start;
        kernels::rotate_columns(chain.data(), rows, rows, first, count, c.data(), s.data(),
                                descending);
        for (int t = 0; t < count; ++t) {
          const int k = descending ? first + count - 1 - t : first + t;
          double* a = single.data() + k * rows;
          for (int i = 0; i < rows; ++i) {
            const double ai = a[i], bi = a[i + rows];
            a[i] = c[t] * ai + s[t] * bi;
            a[i + rows] = c[t] * bi - s[t] * ai;
          }
        }
        for (size_t i = 0; i < chain.size(); ++i) EXPECT_NEAR(chain[i], single[i], 1e-14);
        kernels::rotate(chain.data(), chain.data() + rows, rows, 0.6, 0.8);
        kernels::rotate(chain.data(), chain.data() + rows, rows, 0.6, -0.8);  // its inverse
        for (size_t i = 0; i < chain.size(); ++i) EXPECT_NEAR(chain[i], single[i], 1e-14);
      }
    }
  });
}

TEST(DenseKernels, ReflectionMatchesDenseProduct) {
  std::mt19937 rng(54);
  for_each_path([&] {
    for (const int rows : {1, 3, 4, 7, 8, 9, 15, 16, 30}) {
      for (const int count : {1, 2, 5, 8}) {
        const int lda = rows + 2, first = 1;
        SCOPED_TRACE(testing::Message() << rows << " rows, " << count << " columns");
        std::vector<double> A = random_vector(rng, lda * (first + count + 1));
        const std::vector<double> start = A;
        const std::vector<double> v = random_vector(rng, count);
        double vv = 0.0;
        for (double e : v) vv += e * e;
        const double tau = 2.0 / vv;  // an orthogonal reflection
        kernels::reflect_columns(A.data(), rows, lda, first, count, v.data(), tau);
        // reference: V (I - tau v vᵀ) column by column; everything else untouched
        for (int c = 0; c < first + count + 1; ++c) {
          for (int i = 0; i < lda; ++i) {
            double want = start[c * lda + i];
            if (c >= first && c < first + count && i < rows) {
              double y = 0.0;
              for (int k = 0; k < count; ++k) y += start[(first + k) * lda + i] * v[k];
              want -= tau * y * v[c - first];
            }
            EXPECT_NEAR(A[c * lda + i], want, 1e-13) << "row " << i << " column " << c;
          }
        }
      }
    }
  });
}

TEST(DenseKernels, RowMarginsAndSelectionMatchReferenceLoops) {
  std::mt19937 rng(55);
  const double inf = std::numeric_limits<double>::infinity();
  for_each_path([&] {
    for (const int rows : {0, 1, 3, 4, 5, 8, 13, 42}) {
      for (const int cols : {1, 3, 4, 7, 30}) {
        const int lda = cols + 1;  // of the row-major copy
        SCOPED_TRACE(testing::Message() << rows << "x" << cols);
        const std::vector<double> A = random_vector(rng, lda * rows + 1);
        const int ldc = rows + 2;  // of the column-major copy
        std::vector<double> At(ldc * cols + 1, 0.0);
        for (int i = 0; i < rows; ++i)
          for (int k = 0; k < cols; ++k) At[k * ldc + i] = A[i * lda + k];
        const std::vector<double> x = random_vector(rng, cols);
        std::vector<double> lo = random_vector(rng, rows + 1), hi = lo, scale(rows + 1, 0.5);
        std::vector<double> skip(rows + 1, 0.0);
        for (int i = 0; i < rows; ++i) {
          hi[i] = lo[i] + 0.5;
          if (i % 5 == 1) lo[i] = -inf;  // one-sided rows
          if (i % 7 == 2) hi[i] = inf;
          if (i % 3 == 0) skip[i] = inf;  // active rows are ignored
        }
        std::vector<double> cx(rows + 1, 7.0), margin(rows + 1, 7.0);
        const int best = kernels::column_margins(At.data(), rows, cols, ldc, x.data(), lo.data(),
                                                 hi.data(), scale.data(), skip.data(), cx.data(),
                                                 margin.data());
        int want = -1;
        double want_key = inf;
        for (int i = 0; i < rows; ++i) {
          double ref = 0.0;
          for (int k = 0; k < cols; ++k) ref += A[i * lda + k] * x[k];
          EXPECT_NEAR(cx[i], ref, 1e-13);
          const double want_margin = std::min(ref - lo[i], hi[i] - ref) * scale[i];
          if (std::isinf(want_margin)) {
            EXPECT_EQ(margin[i], want_margin);  // a row without limits
          } else {
            EXPECT_NEAR(margin[i], want_margin, 1e-13);
          }
          const double key = margin[i] + skip[i];
          if (key < want_key) {
            want_key = key;
            want = i;
          }
        }
        EXPECT_EQ(best, want);
        EXPECT_EQ(cx[rows], 7.0);  // nothing written past the end
        EXPECT_EQ(margin[rows], 7.0);

        // the rows with margin at most t, and the same products by index
        std::vector<int> idx(rows + 2, -1);
        const double t = 0.1;
        const int found = kernels::select_at_most(margin.data(), rows, t, rows, idx.data());
        std::vector<int> want_idx;
        for (int i = 0; i < rows; ++i)
          if (margin[i] <= t) want_idx.push_back(i);
        ASSERT_EQ(found, static_cast<int>(want_idx.size()));
        for (int k = 0; k < found; ++k) EXPECT_EQ(idx[k], want_idx[k]);
        if (found >= 2) {
          // the cap stops the search after one more than max_count
          EXPECT_EQ(kernels::select_at_most(margin.data(), rows, t, 1, idx.data()), 2);
        }
        std::vector<double> out(found + 1, 7.0);
        kernels::indexed_row_dots(A.data(), cols, lda, idx.data(), found, x.data(), out.data());
        for (int k = 0; k < found; ++k) EXPECT_NEAR(out[k], cx[idx[k]], 1e-13);
        EXPECT_EQ(out[found], 7.0);
      }
    }
    // nan never qualifies, nor wins
    const std::vector<double> v = {std::nan(""), -1.0, std::nan(""), -2.0, 3.0};
    std::vector<int> idx(6);
    ASSERT_EQ(kernels::select_at_most(v.data(), 5, 0.0, 5, idx.data()), 2);
    EXPECT_EQ(idx[0], 1);
    EXPECT_EQ(idx[1], 3);
  });
}

TEST(DenseKernels, BothPathsSolveTheSameQp) {
  std::mt19937 rng(53);
  const int n = 13, mi = 60;
  auto gauss = [&](int r, int c) {
    std::normal_distribution<double> normal(0.0, 1.0);
    return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(r, c, [&] { return normal(rng); }));
  };
  const Eigen::MatrixXd M = gauss(n, n);
  const Eigen::MatrixXd H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd g = 3.0 * gauss(n, 1);
  const Eigen::MatrixXd C = gauss(mi, n);
  const Eigen::VectorXd l = Eigen::VectorXd::Constant(mi, -1.0), u = Eigen::VectorXd::Ones(mi);
  std::vector<Eigen::VectorXd> solutions;
  for_each_path([&] {
    DenseQp qp(n, 0, mi);
    qp.set_hessian(H);
    qp.set_gradient(g);
    qp.set_inequalities(C, l, u);
    const QpResult& r = qp.solve();
    ASSERT_EQ(r.status, QpStatus::solved);
    EXPECT_LT(r.kkt_residual, 1e-9);
    solutions.push_back(r.x);
  });
  ASSERT_EQ(solutions.size(), 2u);
  EXPECT_LT((solutions[0] - solutions[1]).lpNorm<Eigen::Infinity>(), 1e-12);
}

}  // namespace
}  // namespace mjarm::qp
