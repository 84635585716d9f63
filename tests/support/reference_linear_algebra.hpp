#pragma once
/// @file
/// Dense reference decompositions the tests check mjarm against. They live in one translation
/// unit, compiled once: each of Eigen's decompositions costs several seconds of compile time (far
/// more in the sanitized build) in every test file that would instantiate it.

#include <Eigen/Core>

namespace mjarm::test {

/// A⁻¹ by LU with partial pivoting (A square and invertible).
Eigen::MatrixXd inverse(const Eigen::MatrixXd& A);

/// det(A) by LU with partial pivoting.
double determinant(const Eigen::MatrixXd& A);

/// The numerical rank of A, by LU with full pivoting.
Eigen::Index rank(const Eigen::MatrixXd& A);

/// x with A·x = b by LU with full pivoting (A square of full rank, symmetric or not).
Eigen::VectorXd solve_lu(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

/// x with A·x = b by Cholesky LLᵀ (A symmetric positive definite).
Eigen::VectorXd solve_llt(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

/// x with A·x = b by pivoted LDLᵀ (A symmetric positive or negative semidefinite).
Eigen::VectorXd solve_ldlt(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

/// The eigenvalues of a symmetric A, ascending.
Eigen::VectorXd symmetric_eigenvalues(const Eigen::MatrixXd& A);

/// e^A by Padé approximation with scaling and squaring (Eigen's MatrixFunctions module).
Eigen::MatrixXd matrix_exponential(const Eigen::MatrixXd& A);

}  // namespace mjarm::test
