#pragma once
/// @file
/// The Goldfarb–Idnani factorization of a working set of constraints for a strictly convex QP.
///
/// With H = L·Lᵀ (Cholesky, H ∈ ℝⁿˣⁿ symmetric positive definite) and the q active constraint
/// normals N = [n₁ … n_q] ∈ ℝⁿˣq (linearly independent), the QR factorization
///     L⁻¹·N = Q·[R; 0],   Q ∈ ℝⁿˣⁿ orthogonal, R ∈ ℝqˣq upper triangular,
/// is carried implicitly as J = L⁻ᵀ·Q = [J₁ J₂] (J₁: first q columns) and R. Adding a
/// constraint costs one Householder reflection of the n − q columns of J₂ (Goldfarb & Idnani
/// use n − q − 1 Givens rotations; the reflection does half the flops), dropping one costs
/// q − k − 1 Givens rotations on rows of R (Goldfarb & Idnani 1983, Math. Programming 27:1–33).
/// The class also carries w = Jᵀ·g for the linear term g of the objective, rotated together with
/// J, so that the minimizer of ½xᵀHx + gᵀx on {x : Nᵀx = b} costs O(n²):
///     a = R⁻ᵀ·b,   x = J₁·a − J₂·w₂,   multipliers u = R⁻¹·(a + w₁)   (H·x + g = N·u).
/// Every buffer is allocated by the constructor; no member function allocates afterwards.

#include <Eigen/Core>

namespace mjarm::qp {

/// Dense row-major matrix (rows contiguous), used where rows are the natural access.
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Goldfarb–Idnani working-set factorization (J = L⁻ᵀQ, R) with Givens updates.
class ActiveSetFactor {
 public:
  /// Preallocates every buffer for `n` variables.
  /// @param n number of variables (n ≥ 1)
  /// @throws mjarm::Error if n < 1
  explicit ActiveSetFactor(int n);

  /// Cholesky factorization H = L·Lᵀ (only the lower triangle of `H` is read) and J₀ = L⁻ᵀ.
  /// Leaves the working set empty (J = J₀). Does not allocate.
  /// @param H n×n Hessian
  /// @return false if H is not numerically positive definite (a pivot ≤ 1e-14·max diag(H))
  bool factorize(const Eigen::MatrixXd& H) noexcept;

  /// Whether the last factorize() succeeded.
  bool factorized() const noexcept { return factorized_; }

  /// Empties the working set: J = J₀ = L⁻ᵀ, q = 0. The linear term must be set again
  /// (set_linear_term()) before solve_subproblem().
  void reset() noexcept;

  /// Sets the linear term g of the objective and recomputes w = Jᵀ·g.
  /// @param g n-vector
  void set_linear_term(const Eigen::VectorXd& g) noexcept;

  /// d = Jᵀ·v for a dense constraint normal v (n-vector).
  /// @param v constraint normal, n entries
  /// @param d output, n entries (preallocated by the caller)
  void project(const Eigen::Ref<const Eigen::VectorXd>& v,
               Eigen::Ref<Eigen::VectorXd> d) const noexcept;

  /// d = sign·Jᵀ·e_j for the simple bound normal sign·e_j: the j-th row of J, O(n).
  void project_unit(int j, double sign, Eigen::Ref<Eigen::VectorXd> d) const noexcept;

  /// Squared norm of the part of d = Jᵀv outside the working set, ‖d₂‖² = vᵀ·z with
  /// z = J₂J₂ᵀv the primal step direction of Goldfarb–Idnani.
  double null_space_norm2(const Eigen::VectorXd& d) const noexcept;

  /// r = R⁻¹·d₁: the multipliers expressing the projection of v on the working set normals.
  /// @param d n-vector Jᵀv; only its first q entries are read
  /// @param r output, first q entries written
  void dual_direction(const Eigen::VectorXd& d, Eigen::VectorXd& r) const noexcept;

  /// Whether a normal with d = Jᵀv is linearly independent of the working set:
  /// ‖d₂‖ > tolerance·‖d‖ (and d₂ ≠ 0).
  bool independent(const Eigen::VectorXd& d, double tolerance) const noexcept;

  /// Appends a constraint with d = Jᵀv to the working set (q → q + 1) if it is linearly
  /// independent of it (see independent()); otherwise changes nothing.
  /// @param d n-vector Jᵀv; destroyed (rotated) on success
  /// @param tolerance relative dependence tolerance (e.g. 1e-10)
  /// @return true if added
  bool add(Eigen::VectorXd& d, double tolerance) noexcept;

  /// Removes the working-set constraint at position k (0 ≤ k < q; later ones shift down by one).
  /// @param k position in the working set
  /// @param d optional n-vector Jᵀv of a pending constraint, rotated along with J so that it
  ///          stays equal to Jᵀv afterwards (may be null)
  void drop(int k, Eigen::VectorXd* d) noexcept;

  /// Minimizer of ½xᵀHx + gᵀx subject to Nᵀx = b on the current working set.
  /// R⁻ᵀb is kept between calls: entries whose part of R and b did not change are reused, so
  /// after an add() the call costs one O(q) dot product plus the O(n²) of x.
  /// @param b right-hand sides of the working set, first q entries read
  /// @param x output minimizer (n)
  /// @param u output multipliers with H·x + g = N·u, first q entries written
  void solve_subproblem(const Eigen::VectorXd& b, Eigen::VectorXd& x, Eigen::VectorXd& u) noexcept;

  /// Number of variables n.
  int size() const noexcept { return n_; }
  /// Number of constraints q in the working set.
  int active_count() const noexcept { return q_; }
  /// J = L⁻ᵀQ (n×n).
  const Eigen::MatrixXd& j() const noexcept { return j_; }
  /// R (n×n storage, its leading q×q upper triangle is the factor).
  const Eigen::MatrixXd& r() const noexcept { return r_; }
  /// The Cholesky factor L of H (n×n lower triangular).
  const RowMatrix& l() const noexcept { return l_; }

 private:
  int n_;
  int q_ = 0;
  bool factorized_ = false;
  RowMatrix l_;                // cholesky factor, lower triangular
  Eigen::MatrixXd j0_;         // L^{-T}, upper triangular
  Eigen::MatrixXd j_;          // L^{-T} Q
  Eigen::MatrixXd r_;          // leading q x q upper triangle used
  Eigen::VectorXd w_;          // J^T g
  Eigen::VectorXd inv_diag_;   // 1 / R(i, i), i < q
  Eigen::VectorXd b_;          // right-hand sides of the last solve_subproblem()
  Eigen::VectorXd a_;          // R^{-T} b_, valid in its first solved_ entries
  int solved_ = 0;
  bool j_changed_ = true;      // j_ differs from j0_
  Eigen::VectorXd v_;          // scratch: [a; -w2]
  Eigen::VectorXd h_;          // scratch: householder vector of add()
  Eigen::VectorXd cos_, sin_;  // scratch: parameters of a chain of givens rotations
};

}  // namespace mjarm::qp
