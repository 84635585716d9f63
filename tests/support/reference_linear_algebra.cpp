#include "support/reference_linear_algebra.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

namespace mjarm::test {

Eigen::MatrixXd inverse(const Eigen::MatrixXd& A) { return A.partialPivLu().inverse(); }

double determinant(const Eigen::MatrixXd& A) { return A.partialPivLu().determinant(); }

Eigen::Index rank(const Eigen::MatrixXd& A) { return A.fullPivLu().rank(); }

Eigen::VectorXd solve_lu(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return A.fullPivLu().solve(b);
}

Eigen::VectorXd solve_llt(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return A.llt().solve(b);
}

Eigen::VectorXd solve_ldlt(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  return A.ldlt().solve(b);
}

Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues();
}

Eigen::MatrixXd matrix_exponential(const Eigen::MatrixXd& A) { return A.exp(); }

}  // namespace mjarm::test
