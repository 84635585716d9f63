#include "mjarm/dynamics/task_space.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "task_space_kernels.hpp"

namespace mjarm {

namespace tsk = task_space_kernels;

struct TaskSpaceDynamics::Solver {
  explicit Solver(int size) : eigen(size) {}
  // `compute_eigenvalues` (const) fills the cache through it
  mutable Eigen::SelfAdjointEigenSolver<SmallMatrix> eigen;
};

TaskSpaceDynamics::TaskSpaceDynamics(int dofs, int task_rows, TaskSpaceOptions options)
    : n_(dofs),
      m_(task_rows),
      options_(options),
      solver_(make_workspace<Solver>(std::clamp(task_rows, 1, 6))) {
  if (dofs < 1) throw Error("TaskSpaceDynamics: dofs must be >= 1, got " + std::to_string(dofs));
  if (task_rows < 1 || task_rows > 6) {
    throw Error("TaskSpaceDynamics: task_rows must be in 1..6, got " + std::to_string(task_rows));
  }
  check_fields(options);
  certificate_trace_ = 0.5 / options.min_eigenvalue;
  if (!options.generic_kernels && (n_ == 6 || n_ == 7) && (m_ == 3 || m_ == 6)) {
    kernels_ = n_ == 7 ? (m_ == 6 ? Kernels::n7_m6 : Kernels::n7_m3)
                       : (m_ == 6 ? Kernels::n6_m6 : Kernels::n6_m3);
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
  M_inv_ = Eigen::MatrixXd::Identity(n_, n_);
  N_ = Eigen::MatrixXd::Identity(n_, n_);
  eigenvalues_ = Eigen::VectorXd::Ones(m_);
}

TaskSpaceDynamics::~TaskSpaceDynamics() = default;
TaskSpaceDynamics::TaskSpaceDynamics(const TaskSpaceDynamics& other) = default;
TaskSpaceDynamics& TaskSpaceDynamics::operator=(const TaskSpaceDynamics& other) = default;
TaskSpaceDynamics::TaskSpaceDynamics(TaskSpaceDynamics&& other) noexcept = default;
TaskSpaceDynamics& TaskSpaceDynamics::operator=(TaskSpaceDynamics&& other) noexcept = default;

TaskSpaceStatus TaskSpaceDynamics::update(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                          const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept {
  eigen_assert(M.rows() == n_ && M.cols() == n_ && J.rows() == m_ && J.cols() == n_);
  switch (kernels_) {
    case Kernels::n7_m6:
      return update_sized<7, 6>(M, J);
    case Kernels::n7_m3:
      return update_sized<7, 3>(M, J);
    case Kernels::n6_m6:
      return update_sized<6, 6>(M, J);
    case Kernels::n6_m3:
      return update_sized<6, 3>(M, J);
    case Kernels::generic:
      break;
  }
  return update_sized<0, 0>(M, J);
}

template <int kN, int kM>
TaskSpaceStatus TaskSpaceDynamics::update_sized(
    const Eigen::Ref<const Eigen::MatrixXd>& M,
    const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept {
  // M = L·Lᵀ, read straight from M's lower triangle
  if (!tsk::cholesky<kN>(M.data(), static_cast<int>(M.outerStride()), chol_work_.data(), n_)) {
    status_ = TaskSpaceStatus::not_positive_definite;
    return status_;  // the previous outputs (and their caches) stay as they were
  }
  chol_.swap(chol_work_);
  Jbar_ready_ = M_inv_ready_ = N_ready_ = eigenvalues_ready_ = false;

  // Λ⁻¹ = J·M⁻¹·Jᵀ = Yᵀ·Y with Y = L⁻¹·Jᵀ (exactly symmetric); J is kept for N and Nᵀ·τ₀
  tsk::solve_transposed<kN, kM>(chol_.data(), J.data(), static_cast<int>(J.outerStride()),
                                Y_.data(), J_.data(), n_, m_);
  tsk::gram<kN, kM>(Y_.data(), Lambda_inv_.data(), n_, m_);

  // fast path: Λ⁻¹ = R·Rᵀ, Λ = R⁻ᵀ·R⁻¹, kept when every eigenvalue of Λ⁻¹ is certified above
  // the floor (then the eigen path would floor nothing). The certificate: λ_max(Λ) ≤ trace(Λ),
  // so trace(Λ) ≤ 1/(2·floor) gives λ_min(Λ⁻¹) ≥ 2·floor up to the rounding of Λ (far less than
  // the factor 2); otherwise the exact test, a Cholesky factorization of Λ⁻¹ − floor·I. (The
  // smallest pivot of R is no certificate: every pivot R_jj² is at least λ_min(Λ⁻¹).)
  bool certified = false;
  if (!options_.always_eigendecompose &&
      tsk::cholesky<kM>(Lambda_inv_.data(), m_, small_.data(), m_)) {
    const double trace =
        tsk::inverse_from_factor<kM>(small_.data(), scaled_vectors_.data(), Lambda_.data(), m_);
    certified = trace <= certificate_trace_ || above_floor_exactly();  // NaN: the exact test
  }
  eigendecomposed_ = !certified;
  const bool floored = !certified && eigen_lambda();
  status_ = floored ? TaskSpaceStatus::damped : TaskSpaceStatus::ok;
  return status_;
}

bool TaskSpaceDynamics::above_floor_exactly() noexcept {
  small_ = Lambda_inv_;
  small_.diagonal().array() -= options_.min_eigenvalue;
  return tsk::cholesky<0>(small_.data(), m_, scaled_vectors_.data(), m_);
}

bool TaskSpaceDynamics::eigen_lambda() noexcept {
  // Λ = V·diag(1/max(λ, floor))·Vᵀ: exact when every λ is above the floor, bounded otherwise
  small_ = Lambda_inv_;
  solver_->eigen.compute(small_, Eigen::ComputeEigenvectors);
  eigenvalues_ = solver_->eigen.eigenvalues();
  eigenvalues_ready_ = true;
  bool floored = false;
  for (int k = 0; k < m_; ++k) {
    const double lambda = eigenvalues_[k];
    const bool low = !(lambda >= options_.min_eigenvalue);  // NaN counts as low
    floored = floored || low;
    scaled_[k] = 1.0 / (low ? options_.min_eigenvalue : lambda);
  }
  const auto& V = solver_->eigen.eigenvectors();
  scaled_vectors_.noalias() = V * scaled_.asDiagonal();
  small_.noalias() = scaled_vectors_ * V.transpose();
  Lambda_ = small_;
  return floored;
}

void TaskSpaceDynamics::compute_eigenvalues() const noexcept {
  solver_->eigen.compute(Lambda_inv_, Eigen::EigenvaluesOnly);
  eigenvalues_ = solver_->eigen.eigenvalues();
  eigenvalues_ready_ = true;
}

TaskSpaceStatus TaskSpaceDynamics::update(const ChainDynamics& dynamics) noexcept {
  return update(dynamics.mass_matrix(), dynamics.jacobian().topRows(m_));
}

const Eigen::MatrixXd& TaskSpaceDynamics::mass_inverse() const noexcept {
  if (!M_inv_ready_) {
    M_inv_.setIdentity();
    for (int c = 0; c < n_; ++c) {
      double* x = M_inv_.data() + c * n_;
      tsk::forward_solve<0>(chol_.data(), x, n_);
      tsk::backward_solve<0>(chol_.data(), x, n_);
    }
    M_inv_ready_ = true;
  }
  return M_inv_;
}

const Eigen::MatrixXd& TaskSpaceDynamics::jbar() const noexcept {
  if (!Jbar_ready_) {
    // M⁻¹·Jᵀ = L⁻ᵀ·Y, then J̄ = M⁻¹·Jᵀ·Λ
    MinvJt_ = Y_;
    for (int c = 0; c < m_; ++c) tsk::backward_solve<0>(chol_.data(), MinvJt_.data() + c * n_, n_);
    tsk::multiply<0, 0>(MinvJt_.data(), Lambda_.data(), Jbar_.data(), n_, m_);
    Jbar_ready_ = true;
  }
  return Jbar_;
}

const Eigen::MatrixXd& TaskSpaceDynamics::nullspace() const noexcept {
  if (!N_ready_) {
    const Eigen::MatrixXd& Jbar = jbar();
    for (int c = 0; c < n_; ++c) {
      double* out = N_.data() + c * n_;
      for (int i = 0; i < n_; ++i) out[i] = i == c ? 1.0 : 0.0;
      for (int k = 0; k < m_; ++k) {
        const double j = J_(k, c);
        const double* in = Jbar.data() + k * n_;
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
  switch (kernels_) {
    case Kernels::n7_m6:
      return project_sized<7, 6>(tau0.data(), tau.data());
    case Kernels::n7_m3:
      return project_sized<7, 3>(tau0.data(), tau.data());
    case Kernels::n6_m6:
      return project_sized<6, 6>(tau0.data(), tau.data());
    case Kernels::n6_m3:
      return project_sized<6, 3>(tau0.data(), tau.data());
    case Kernels::generic:
      break;
  }
  project_sized<0, 0>(tau0.data(), tau.data());
}

template <int kN, int kM>
void TaskSpaceDynamics::project_sized(const double* tau0, double* tau) const noexcept {
  // Nᵀ·τ₀ = τ₀ − Jᵀ·s with s = J̄ᵀ·τ₀ = Λ·Yᵀ·(L⁻¹·τ₀); tau holds L⁻¹·τ₀ meanwhile
  const int n = tsk::size_or<kN>(n_);
  const int m = tsk::size_or<kM>(m_);
  for (int i = 0; i < n; ++i) tau[i] = tau0[i];
  tsk::forward_solve<kN>(chol_.data(), tau, n);
  double w[6];
  for (int c = 0; c < m; ++c) {
    const double* y = Y_.data() + c * n;
    double acc = 0.0;
    for (int i = 0; i < n; ++i) acc += y[i] * tau[i];
    w[c] = acc;
  }
  double s[6];
  for (int c = 0; c < m; ++c) {
    double acc = 0.0;
    for (int k = 0; k < m; ++k) acc += Lambda_.data()[c + k * m] * w[k];
    s[c] = acc;
  }
  const double* J = J_.data();
  for (int i = 0; i < n; ++i) {
    double acc = tau0[i];
    for (int c = 0; c < m; ++c) acc -= J[c + i * m] * s[c];
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
