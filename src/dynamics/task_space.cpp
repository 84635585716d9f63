#include "mjarm/dynamics/task_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

const char* to_string(TaskSpaceStatus status) noexcept {
  switch (status) {
    case TaskSpaceStatus::ok: return "ok";
    case TaskSpaceStatus::damped: return "damped";
    case TaskSpaceStatus::not_positive_definite: return "not_positive_definite";
  }
  return "unknown";
}

TaskSpaceDynamics::TaskSpaceDynamics(int dofs, int task_rows, TaskSpaceOptions options)
    : n_(dofs),
      m_(task_rows),
      options_(options),
      llt_(std::max(dofs, 1)),
      eigen_(std::clamp(task_rows, 1, 6)) {
  if (dofs < 1) throw Error("TaskSpaceDynamics: dofs must be >= 1, got " + std::to_string(dofs));
  if (task_rows < 1 || task_rows > 6) {
    throw Error("TaskSpaceDynamics: task_rows must be in 1..6, got " + std::to_string(task_rows));
  }
  if (!(options.min_eigenvalue > 0.0) || !std::isfinite(options.min_eigenvalue)) {
    throw Error("TaskSpaceDynamics: options.min_eigenvalue must be > 0 and finite, got " +
                std::to_string(options.min_eigenvalue));
  }
  small_ = SmallMatrix::Zero(m_, m_);
  M_inv_ = Eigen::MatrixXd::Identity(n_, n_);
  MinvJt_ = Eigen::MatrixXd::Zero(n_, m_);
  Lambda_inv_ = Eigen::MatrixXd::Identity(m_, m_);
  Lambda_ = Eigen::MatrixXd::Identity(m_, m_);
  Jbar_ = Eigen::MatrixXd::Zero(n_, m_);
  N_ = Eigen::MatrixXd::Identity(n_, n_);
  eigenvalues_ = Eigen::VectorXd::Ones(m_);
  scaled_ = SmallVector::Ones(m_);
  scaled_vectors_ = SmallMatrix::Zero(m_, m_);
}

TaskSpaceStatus TaskSpaceDynamics::update(const Eigen::Ref<const Eigen::MatrixXd>& M,
                                          const Eigen::Ref<const Eigen::MatrixXd>& J) noexcept {
  eigen_assert(M.rows() == n_ && M.cols() == n_ && J.rows() == m_ && J.cols() == n_);
  llt_.compute(M);
  if (llt_.info() != Eigen::Success) {
    status_ = TaskSpaceStatus::not_positive_definite;
    return status_;
  }
  M_inv_.setIdentity();
  llt_.solveInPlace(M_inv_);
  MinvJt_ = J.transpose();
  llt_.solveInPlace(MinvJt_);
  Lambda_inv_.noalias() = J * MinvJt_;
  // the product is symmetric up to rounding; make it exactly so for the eigen solver
  small_ = 0.5 * (Lambda_inv_ + Lambda_inv_.transpose());
  Lambda_inv_ = small_;

  // Λ = V·diag(1/max(λ, floor))·Vᵀ: exact when every λ is above the floor, bounded otherwise
  eigen_.compute(small_, Eigen::ComputeEigenvectors);
  eigenvalues_ = eigen_.eigenvalues();
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

  Jbar_.noalias() = MinvJt_ * Lambda_;
  N_.setIdentity();
  N_.noalias() -= Jbar_ * J;
  status_ = floored ? TaskSpaceStatus::damped : TaskSpaceStatus::ok;
  return status_;
}

TaskSpaceStatus TaskSpaceDynamics::update(const ChainDynamics& dynamics) noexcept {
  return update(dynamics.mass_matrix(), dynamics.jacobian().topRows(m_));
}

void TaskSpaceDynamics::project_torque(const Eigen::Ref<const Eigen::VectorXd>& tau0,
                                       Eigen::Ref<Eigen::VectorXd> tau) const noexcept {
  tau.noalias() = N_.transpose() * tau0;
}

double TaskSpaceDynamics::min_singular_value() const noexcept {
  return std::sqrt(std::max(eigenvalues_[0], 0.0));
}

double TaskSpaceDynamics::condition() const noexcept {
  const double low = eigenvalues_[0];
  if (!(low > 0.0)) return std::numeric_limits<double>::infinity();
  return eigenvalues_[m_ - 1] / low;
}

}  // namespace mjarm
