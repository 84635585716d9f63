#include "mjarm/control/adaptive_compliance.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "control_checks.hpp"

namespace mjarm {

struct AdaptiveCompliance::Solver {
  Eigen::SelfAdjointEigenSolver<Matrix6d> eigen;
};

AdaptiveCompliance::AdaptiveCompliance(const AdaptiveComplianceOptions& options)
    : options_(options), eigen_(make_workspace<Solver>()) {
  const Matrix6d& K0 = options.stiffness;
  if (!K0.allFinite()) {
    throw Error("hqp-ac: stiffness K0 must be finite, got diagonal " +
                detail::values_text(K0.diagonal()));
  }
  const double scale = std::max(1.0, K0.cwiseAbs().maxCoeff());
  if ((K0 - K0.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    throw Error("hqp-ac: stiffness K0 must be symmetric");
  }
  Eigen::SelfAdjointEigenSolver<Matrix6d> solver(K0);
  const Vector6d eig = solver.eigenvalues();
  if (!(eig[0] > 1e-12 * scale)) {
    throw Error("hqp-ac: stiffness K0 must be symmetric positive definite; its eigenvalues are " +
                detail::values_text(eig));
  }
  K0_sqrt_ =
      solver.eigenvectors() * eig.cwiseSqrt().asDiagonal() * solver.eigenvectors().transpose();
  check_fields(options, "hqp-ac");
  update(Vector6d::Zero(), Matrix6d::Identity());
}

AdaptiveCompliance::~AdaptiveCompliance() = default;
AdaptiveCompliance::AdaptiveCompliance(const AdaptiveCompliance& other) = default;
AdaptiveCompliance& AdaptiveCompliance::operator=(const AdaptiveCompliance& other) = default;
AdaptiveCompliance::AdaptiveCompliance(AdaptiveCompliance&& other) noexcept = default;
AdaptiveCompliance& AdaptiveCompliance::operator=(AdaptiveCompliance&& other) noexcept = default;

void AdaptiveCompliance::update(const Vector6d& F,
                                const Eigen::Ref<const Eigen::MatrixXd>& Lambda_inv) noexcept {
  const double norm = F.allFinite() ? F.norm() : 0.0;
  force_ = std::max(norm - options_.deadband, 0.0);
  alpha_ = 1.0 / (1.0 + std::exp(-options_.force_gain * force_));
  scale_ = std::clamp(1.0 - alpha_, options_.min_stiffness_ratio, 1.0);
  K_ = scale_ * options_.stiffness;

  // Λ^½ from the eigen-decomposition of Λ⁻¹, its small eigenvalues floored
  eigen_->eigen.compute(Lambda_inv.topLeftCorner<6, 6>());
  Vector6d d;
  for (int i = 0; i < 6; ++i) {
    d[i] = 1.0 / std::sqrt(std::max(eigen_->eigen.eigenvalues()[i], options_.min_eigenvalue));
  }
  const Matrix6d& V = eigen_->eigen.eigenvectors();
  Lambda_sqrt_.noalias() = V * d.asDiagonal() * V.transpose();
  // D_r = √s·(Λ^½·K0^½ + K0^½·Λ^½)
  D_.noalias() = Lambda_sqrt_ * K0_sqrt_;
  D_ = std::sqrt(scale_) * (D_ + D_.transpose()).eval();
}

double AdaptiveCompliance::damping_min_eigenvalue() const noexcept {
  Eigen::SelfAdjointEigenSolver<Matrix6d> solver(D_, Eigen::EigenvaluesOnly);
  return solver.eigenvalues()[0];
}

}  // namespace mjarm
