#include "mjarm/ik/damped_least_squares.hpp"

#include <Eigen/Cholesky>
#include <string>

#include "mjarm/error.hpp"

namespace mjarm {

struct DampedLeastSquares::Factor {
  Eigen::LLT<Eigen::MatrixXd> llt;
};

DampedLeastSquares::DampedLeastSquares(int rows, int cols) : llt_(make_workspace<Factor>()) {
  if (rows <= 0 || cols <= 0) {
    throw Error("damped least squares needs a positive size, got " + std::to_string(rows) + "×" +
                std::to_string(cols));
  }
  A_.setZero(rows, rows);
  // factor something once so the LLT holds its storage and a defined state (copies read it)
  llt_->llt.compute(Eigen::MatrixXd::Identity(rows, rows));
  y_m_.setZero(rows);
  y_n_.setZero(cols);
  X_.setZero(rows, cols);
}

DampedLeastSquares::~DampedLeastSquares() = default;
DampedLeastSquares::DampedLeastSquares(const DampedLeastSquares& other) = default;
DampedLeastSquares& DampedLeastSquares::operator=(const DampedLeastSquares& other) = default;
DampedLeastSquares::DampedLeastSquares(DampedLeastSquares&& other) noexcept = default;
DampedLeastSquares& DampedLeastSquares::operator=(DampedLeastSquares&& other) noexcept = default;

bool DampedLeastSquares::factor(const Eigen::Ref<const Eigen::MatrixXd>& J,
                                double damping_sq) noexcept {
  A_.noalias() = J * J.transpose();
  A_.diagonal().array() += damping_sq;
  if (!A_.allFinite()) return false;
  llt_->llt.compute(A_);
  return llt_->llt.info() == Eigen::Success;
}

void DampedLeastSquares::step(const Eigen::Ref<const Eigen::MatrixXd>& J,
                              const Eigen::Ref<const Eigen::VectorXd>& e,
                              Eigen::Ref<Eigen::VectorXd> dq) noexcept {
  y_m_ = e;
  llt_->llt.solveInPlace(y_m_);
  dq.noalias() = J.transpose() * y_m_;
}

void DampedLeastSquares::project(const Eigen::Ref<const Eigen::MatrixXd>& J,
                                 const Eigen::Ref<const Eigen::VectorXd>& v,
                                 Eigen::Ref<Eigen::VectorXd> out) noexcept {
  y_m_.noalias() = J * v;
  llt_->llt.solveInPlace(y_m_);
  y_n_.noalias() = J.transpose() * y_m_;
  // v and out may alias: y_n_ is complete before out is written
  out = v - y_n_;
}

void DampedLeastSquares::row_space_projector(const Eigen::Ref<const Eigen::MatrixXd>& J,
                                             Eigen::Ref<Eigen::MatrixXd> P) noexcept {
  X_ = J;
  llt_->llt.solveInPlace(X_);
  P.noalias() = J.transpose() * X_;
}

}  // namespace mjarm
