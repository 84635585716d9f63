#include "mjarm/dynamics/task_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {
namespace {

// Dense kernels on column-major storage with leading dimension = rows. The sizes here are tiny
// (n ≈ 7, m ≤ 6): plain loops beat Eigen's blocked dynamic-size kernels several times over.

// In-place lower Cholesky a = L·Lᵀ of the n×n symmetric matrix a (reads the lower triangle);
// false when a pivot is not > 0 (or NaN): not positive definite.
bool cholesky(double* a, int n) noexcept {
  for (int j = 0; j < n; ++j) {
    double* col_j = a + j * n;
    for (int k = 0; k < j; ++k) {
      // subtract column k's contribution from column j (rows j..n-1)
      const double* col_k = a + k * n;
      const double l_jk = col_k[j];
      for (int i = j; i < n; ++i) col_j[i] -= col_k[i] * l_jk;
    }
    if (!(col_j[j] > 0.0)) return false;
    const double l = std::sqrt(col_j[j]);
    col_j[j] = l;
    const double inv = 1.0 / l;
    for (int i = j + 1; i < n; ++i) col_j[i] *= inv;
  }
  return true;
}

// b ← L⁻¹·b for the n×cols matrix b (L lower, n×n).
void forward_solve(const double* L, int n, double* b, int cols) noexcept {
  for (int c = 0; c < cols; ++c) {
    double* x = b + c * n;
    for (int k = 0; k < n; ++k) {
      const double* col_k = L + k * n;
      x[k] /= col_k[k];
      const double xk = x[k];
      for (int i = k + 1; i < n; ++i) x[i] -= col_k[i] * xk;
    }
  }
}

// b ← L⁻ᵀ·b for the n×cols matrix b (L lower, n×n).
void backward_solve(const double* L, int n, double* b, int cols) noexcept {
  for (int c = 0; c < cols; ++c) {
    double* x = b + c * n;
    for (int i = n - 1; i >= 0; --i) {
      const double* col_i = L + i * n;
      double s = x[i];
      for (int k = i + 1; k < n; ++k) s -= col_i[k] * x[k];
      x[i] = s / col_i[i];
    }
  }
}

// g ← yᵀ·y (cols×cols, exactly symmetric) for the rows×cols matrix y.
void gram(const double* y, int rows, int cols, double* g) noexcept {
  for (int a = 0; a < cols; ++a) {
    for (int b = a; b < cols; ++b) {
      double s = 0.0;
      for (int i = 0; i < rows; ++i) s += y[i + a * rows] * y[i + b * rows];
      g[a + b * cols] = s;
      g[b + a * cols] = s;
    }
  }
}

}  // namespace

const char* to_string(TaskSpaceStatus status) noexcept {
  switch (status) {
    case TaskSpaceStatus::ok:
      return "ok";
    case TaskSpaceStatus::damped:
      return "damped";
    case TaskSpaceStatus::not_positive_definite:
      return "not_positive_definite";
  }
  return "unknown";
}

TaskSpaceDynamics::TaskSpaceDynamics(int dofs, int task_rows, TaskSpaceOptions options)
    : n_(dofs), m_(task_rows), options_(options), eigen_(std::clamp(task_rows, 1, 6)) {
  if (dofs < 1) throw Error("TaskSpaceDynamics: dofs must be >= 1, got " + std::to_string(dofs));
  if (task_rows < 1 || task_rows > 6) {
    throw Error("TaskSpaceDynamics: task_rows must be in 1..6, got " + std::to_string(task_rows));
  }
  if (!(options.min_eigenvalue > 0.0) || !std::isfinite(options.min_eigenvalue)) {
    throw Error("TaskSpaceDynamics: options.min_eigenvalue must be > 0 and finite, got " +
                std::to_string(options.min_eigenvalue));
  }
  chol_ = Eigen::MatrixXd::Identity(n_, n_);
  chol_work_ = Eigen::MatrixXd::Identity(n_, n_);
  J_ = Eigen::MatrixXd::Zero(m_, n_);
  Y_ = Eigen::MatrixXd::Zero(n_, m_);
  MinvJt_ = Eigen::MatrixXd::Zero(n_, m_);
  Lambda_inv_ = Eigen::MatrixXd::Identity(m_, m_);
  Lambda_ = Eigen::MatrixXd::Identity(m_, m_);
  Jbar_ = Eigen::MatrixXd::Zero(n_, m_);
  small_ = SmallMatrix::Zero(m_, m_);
  scaled_vectors_ = SmallMatrix::Zero(m_, m_);
  scaled_ = SmallVector::Ones(m_);
  work_ = Eigen::VectorXd::Zero(n_);
  M_inv_ = Eigen::MatrixXd::Identity(n_, n_);
  N_ = Eigen::MatrixXd::Identity(n_, n_);
  eigenvalues_ = Eigen::VectorXd::Ones(m_);
}

TaskSpaceStatus TaskSpaceDynamics::update(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                          const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept {
  eigen_assert(M.rows() == n_ && M.cols() == n_ && J.rows() == m_ && J.cols() == n_);
  chol_work_ = M;
  if (!cholesky(chol_work_.data(), n_)) {
    status_ = TaskSpaceStatus::not_positive_definite;
    return status_;  // the previous outputs (and their caches) stay as they were
  }
  chol_.swap(chol_work_);
  J_ = J;
  M_inv_ready_ = N_ready_ = eigenvalues_ready_ = false;

  // Λ⁻¹ = J·M⁻¹·Jᵀ = Yᵀ·Y with Y = L⁻¹·Jᵀ (exactly symmetric); M⁻¹·Jᵀ = L⁻ᵀ·Y
  Y_ = J_.transpose();
  forward_solve(chol_.data(), n_, Y_.data(), m_);
  gram(Y_.data(), n_, m_, Lambda_inv_.data());
  MinvJt_ = Y_;
  backward_solve(chol_.data(), n_, MinvJt_.data(), m_);

  // fast path: Λ⁻¹ − floor·I positive definite (its Cholesky succeeds) certifies that every
  // eigenvalue of Λ⁻¹ is above the floor, so the eigen path would floor nothing; then
  // Λ⁻¹ = R·Rᵀ and Λ = R⁻ᵀ·R⁻¹.
  bool floored = false;
  bool certified = false;
  if (!options_.always_eigendecompose) {
    small_ = Lambda_inv_;
    small_.diagonal().array() -= options_.min_eigenvalue;
    if (cholesky(small_.data(), m_)) {
      small_ = Lambda_inv_;
      certified = cholesky(small_.data(), m_);
    }
    if (certified) {
      scaled_vectors_.setIdentity();
      forward_solve(small_.data(), m_, scaled_vectors_.data(), m_);
      gram(scaled_vectors_.data(), m_, m_, Lambda_.data());
    }
  }
  eigendecomposed_ = !certified;
  if (!certified) floored = eigen_lambda();

  // J̄ = M⁻¹·Jᵀ·Λ (n×m)
  for (int c = 0; c < m_; ++c) {
    double* out = Jbar_.data() + c * n_;
    std::fill(out, out + n_, 0.0);
    for (int k = 0; k < m_; ++k) {
      const double l = Lambda_(k, c);
      const double* in = MinvJt_.data() + k * n_;
      for (int i = 0; i < n_; ++i) out[i] += in[i] * l;
    }
  }
  status_ = floored ? TaskSpaceStatus::damped : TaskSpaceStatus::ok;
  return status_;
}

bool TaskSpaceDynamics::eigen_lambda() noexcept {
  // Λ = V·diag(1/max(λ, floor))·Vᵀ: exact when every λ is above the floor, bounded otherwise
  small_ = Lambda_inv_;
  eigen_.compute(small_, Eigen::ComputeEigenvectors);
  eigenvalues_ = eigen_.eigenvalues();
  eigenvalues_ready_ = true;
  bool floored = false;
  for (int k = 0; k < m_; ++k) {
    const double lambda = eigenvalues_[k];
    const bool low = !(lambda >= options_.min_eigenvalue);  // NaN counts as low
    floored = floored || low;
    scaled_[k] = 1.0 / (low ? options_.min_eigenvalue : lambda);
  }
  const auto& V = eigen_.eigenvectors();
  scaled_vectors_.noalias() = V * scaled_.asDiagonal();
  small_.noalias() = scaled_vectors_ * V.transpose();
  Lambda_ = small_;
  return floored;
}

void TaskSpaceDynamics::compute_eigenvalues() const noexcept {
  eigen_.compute(Lambda_inv_, Eigen::EigenvaluesOnly);
  eigenvalues_ = eigen_.eigenvalues();
  eigenvalues_ready_ = true;
}

TaskSpaceStatus TaskSpaceDynamics::update(const ChainDynamics& dynamics) noexcept {
  return update(dynamics.mass_matrix(), dynamics.jacobian().topRows(m_));
}

const Eigen::MatrixXd& TaskSpaceDynamics::mass_inverse() const noexcept {
  if (!M_inv_ready_) {
    M_inv_.setIdentity();
    forward_solve(chol_.data(), n_, M_inv_.data(), n_);
    backward_solve(chol_.data(), n_, M_inv_.data(), n_);
    M_inv_ready_ = true;
  }
  return M_inv_;
}

const Eigen::MatrixXd& TaskSpaceDynamics::nullspace() const noexcept {
  if (!N_ready_) {
    for (int c = 0; c < n_; ++c) {
      double* out = N_.data() + c * n_;
      for (int i = 0; i < n_; ++i) out[i] = i == c ? 1.0 : 0.0;
      for (int k = 0; k < m_; ++k) {
        const double j = J_(k, c);
        const double* in = Jbar_.data() + k * n_;
        for (int i = 0; i < n_; ++i) out[i] -= in[i] * j;
      }
    }
    N_ready_ = true;
  }
  return N_;
}

const Eigen::VectorXd& TaskSpaceDynamics::eigenvalues() const noexcept {
  if (!eigenvalues_ready_) compute_eigenvalues();
  return eigenvalues_;
}

void TaskSpaceDynamics::project_torque(const Eigen::Ref<const Eigen::VectorXd>& tau0,
                                       Eigen::Ref<Eigen::VectorXd> tau) const noexcept {
  // Nᵀ·τ₀ = τ₀ − Jᵀ·(J̄ᵀ·τ₀): 4·n·m flops instead of n²·m for N
  double s[6];
  for (int c = 0; c < m_; ++c) {
    const double* col = Jbar_.data() + c * n_;
    double acc = 0.0;
    for (int i = 0; i < n_; ++i) acc += col[i] * tau0[i];
    s[c] = acc;
  }
  for (int i = 0; i < n_; ++i) {
    double acc = tau0[i];
    for (int c = 0; c < m_; ++c) acc -= J_(c, i) * s[c];
    tau[i] = acc;
  }
}

double TaskSpaceDynamics::min_singular_value() const noexcept {
  return std::sqrt(std::max(eigenvalues()[0], 0.0));
}

double TaskSpaceDynamics::condition() const noexcept {
  const Eigen::VectorXd& lambda = eigenvalues();
  const double low = lambda[0];
  if (!(low > 0.0)) return std::numeric_limits<double>::infinity();
  return lambda[m_ - 1] / low;
}

}  // namespace mjarm
