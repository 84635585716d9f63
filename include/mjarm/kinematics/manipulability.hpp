#pragma once
/// @file
/// Yoshikawa manipulability, singular values and condition number of a chain's frame Jacobian,
/// with the analytic gradient ∂w/∂q. Preallocated: evaluating allocates nothing.

#include <Eigen/Core>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/types.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/workspace_ptr.hpp"

namespace mjarm {

/// Which rows of the world-aligned frame Jacobian J_WE (6 × n, linear first) are measured.
enum class JacobianBlock {
  full,        ///< all 6 rows [v; ω] (mixes m/rad and rad/rad: σ depend on the length unit)
  position,    ///< rows 0–2: velocity of the frame origin [m per rad or m per m]
  orientation  ///< rows 3–5: angular velocity [rad per rad]
};

constexpr auto declared_names(const JacobianBlock*) {
  using B = JacobianBlock;
  return std::array{EnumName{B::full, "full", "all 6 rows [v; ω]"},
                    EnumName{B::position, "position", "rows 0–2: velocity of the frame origin"},
                    EnumName{B::orientation, "orientation", "rows 3–5: angular velocity"}};
}

/// How close a configuration is to a singularity, judged on the inverse condition number
/// σmin/σmax of the measured Jacobian block.
enum class SingularityStatus {
  regular,        ///< σmin/σmax ≥ near_singular_threshold
  near_singular,  ///< singular_tolerance < σmin/σmax < near_singular_threshold
  singular        ///< σmin/σmax ≤ singular_tolerance (or σmax = 0): a direction is lost
};

constexpr auto declared_names(const SingularityStatus*) {
  using S = SingularityStatus;
  return std::array{EnumName{S::regular, "regular", "σmin/σmax ≥ near_singular_threshold"},
                    EnumName{S::near_singular, "near_singular", "between the two thresholds"},
                    EnumName{S::singular, "singular", "σmin/σmax ≤ singular_tolerance"}};
}

/// Settings of `Manipulability`.
struct ManipulabilityOptions {
  JacobianBlock block = JacobianBlock::full;  ///< rows of J measured
  double singular_tolerance = 1e-9;           ///< σmin/σmax at or below this: singular
  double near_singular_threshold = 1e-2;      ///< σmin/σmax below this: near-singular
};

constexpr auto declared_fields(const ManipulabilityOptions*) {
  using S = ManipulabilityOptions;
  return declare<S>(
      "manipulability", field("block", &S::block, "rows of J measured"),
      field("singular_tolerance", &S::singular_tolerance, "", Range::non_negative(),
            "σmin/σmax at or below this: singular"),
      field("near_singular_threshold", &S::near_singular_threshold, "", Range::non_negative(),
            "σmin/σmax below this: near-singular (≥ singular_tolerance)"));
}

/// One evaluation. With m rows measured and n joints, p = min(m, n) singular values are used.
struct ManipulabilityResult {
  /// Yoshikawa manipulability w = σ1·…·σp = √det(J Jᵀ) when n ≥ m (√det(Jᵀ J) when n < m).
  double manipulability = 0.0;
  double sigma_max = 0.0;  ///< largest singular value σ1
  double sigma_min = 0.0;  ///< smallest singular value σp
  /// σmax/σmin; +infinity when the status is `singular`.
  double condition_number = 0.0;
  SingularityStatus status = SingularityStatus::singular;
};

/// Singular values, at most 6 (stored without heap allocation), sorted decreasing.
using SingularValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

/// Manipulability measures of one chain, with all workspace preallocated at construction.
///
/// The gradient is analytic: ∂w/∂q_i = w·tr(J⁺ ∂J/∂q_i) = Σ_k (Π_{l≠k} σ_l)·u_kᵀ (∂J/∂q_i) v_k,
/// with ∂J/∂q_i built from the joint axes and anchors of `ChainKinematics`. The cofactor form
/// Π_{l≠k} σ_l never divides by a singular value, so it stays finite near singularities; at an
/// exact singularity (status `singular`) w is not differentiable and the gradient is set to 0.
class Manipulability {
 public:
  /// @throws Error when a threshold is negative or not finite, or singular_tolerance exceeds
  /// near_singular_threshold.
  explicit Manipulability(const Chain& chain, const ManipulabilityOptions& options = {});
  ~Manipulability();
  Manipulability(const Manipulability& other);
  Manipulability& operator=(const Manipulability& other);
  Manipulability(Manipulability&& other) noexcept;
  Manipulability& operator=(Manipulability&& other) noexcept;

  const Chain& chain() const noexcept { return kin_.chain(); }
  const ManipulabilityOptions& options() const noexcept { return options_; }
  /// Number of Jacobian rows measured (6 or 3).
  int rows() const noexcept { return rows_; }

  /// Evaluates at joint values @p q (chain order, n values). Allocates nothing.
  /// @throws Error when @p q has the wrong size or holds NaN/inf.
  const ManipulabilityResult& evaluate(const Eigen::Ref<const Eigen::VectorXd>& q);

  /// Evaluates at @p q and writes ∂w/∂q (n values, units of w per rad or per m) into
  /// @p gradient; zero at an exact singularity. Allocates nothing.
  /// @throws Error when @p q or @p gradient has the wrong size or @p q holds NaN/inf.
  const ManipulabilityResult& evaluate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       Eigen::Ref<Eigen::VectorXd> gradient);

  /// Result of the last evaluation.
  const ManipulabilityResult& result() const noexcept { return result_; }
  /// Singular values of the measured block at the last evaluation (p = min(m, n) values).
  const SingularValues& singular_values() const noexcept { return sigma_; }
  /// The measured block of J_WE (m × n, world-aligned) at the last evaluation.
  const Eigen::MatrixXd& jacobian_block() const noexcept { return J_block_; }
  /// The kinematics used, holding the pose X_WE of the last evaluation. Configure joints held
  /// outside the chain with `kinematics().set_fixed_qpos(...)`.
  ChainKinematics& kinematics() noexcept { return kin_; }
  const ChainKinematics& kinematics() const noexcept { return kin_; }

  /// ∂J_WE/∂q_i at the last evaluation (6 × n, world-aligned, linear first), from the joint
  /// axes and anchors. Exposed for tests; the gradient never forms it.
  void jacobian_derivative(int i, Eigen::Ref<Matrix6Xd> dJ) const;

 private:
  void compute(const Eigen::Ref<const Eigen::VectorXd>& q, bool vectors) noexcept;
  void compute_gradient(Eigen::Ref<Eigen::VectorXd> gradient) noexcept;
  /// Derivative of column j of J_WE with respect to q_i (6 values).
  Vector6d column_derivative(int i, int j) const noexcept;

  ManipulabilityOptions options_;
  ChainKinematics kin_;
  int rows_ = 6;
  int first_row_ = 0;
  std::vector<char> hinge_;    // per chain joint: hinge (true) or slide
  std::vector<int> joint_id_;  // per chain joint: model joint id (path order = id order)
  // workspace
  Matrix6Xd J_;
  Eigen::MatrixXd J_block_;
  struct Svds;  // the two SVDs of J_block_ (in the .cpp: Eigen/SVD)
  WorkspacePtr<Svds> svd_;
  SingularValues sigma_;
  Matrix6Xd weights_;  // U·diag(Π_{l≠k} σ_l)·Vᵀ in the 6 rows, zero outside the block
  ManipulabilityResult result_;
};

/// Manipulability of the chain's frame at @p q, for one-off use (builds a `Manipulability`).
/// @throws Error when @p q has the wrong size or holds NaN/inf.
ManipulabilityResult manipulability(const Chain& chain, const Eigen::VectorXd& q,
                                    const ManipulabilityOptions& options = {});

}  // namespace mjarm
