#include "mjarm/kinematics/manipulability.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

struct Manipulability::Svds {
  // preallocating both decompositions keeps compute() free of heap allocation
  Svds(int rows, int cols)
      : values(rows, cols), vectors(rows, cols, Eigen::ComputeThinU | Eigen::ComputeThinV) {}
  Eigen::JacobiSVD<Eigen::MatrixXd> values;   // singular values only
  Eigen::JacobiSVD<Eigen::MatrixXd> vectors;  // with thin U and V, for the gradient
};

Manipulability::Manipulability(const Chain& chain, const ManipulabilityOptions& options)
    : options_(options), kin_(chain) {
  check_fields(options);
  if (options.singular_tolerance > options.near_singular_threshold) {
    throw Error("manipulability thresholds must satisfy 0 <= singular_tolerance (" +
                number_text(options.singular_tolerance) + ") <= near_singular_threshold (" +
                number_text(options.near_singular_threshold) + ")");
  }
  rows_ = options.block == JacobianBlock::full ? 6 : 3;
  first_row_ = options.block == JacobianBlock::orientation ? 3 : 0;
  const int n = chain.size();
  const mjModel& m = chain.robot().model();
  hinge_.resize(n);
  joint_id_.resize(n);
  for (int i = 0; i < n; ++i) {
    joint_id_[i] = chain.joint_id(i);
    hinge_[i] = m.jnt_type[joint_id_[i]] == mjJNT_HINGE;
  }
  J_.setZero(6, n);
  J_block_.setZero(rows_, n);
  svd_ = make_workspace<Svds>(rows_, n);
  sigma_.setZero(std::min(rows_, n));
  weights_.setZero(6, n);
}

Manipulability::~Manipulability() = default;
Manipulability::Manipulability(const Manipulability& other) = default;
Manipulability& Manipulability::operator=(const Manipulability& other) = default;
Manipulability::Manipulability(Manipulability&& other) noexcept = default;
Manipulability& Manipulability::operator=(Manipulability&& other) noexcept = default;

const ManipulabilityResult& Manipulability::evaluate(const Eigen::Ref<const Eigen::VectorXd>& q) {
  chain().check(q, "q");
  compute(q, false);
  return result_;
}

const ManipulabilityResult& Manipulability::evaluate(const Eigen::Ref<const Eigen::VectorXd>& q,
                                                     Eigen::Ref<Eigen::VectorXd> gradient) {
  chain().check(q, "q");
  if (gradient.size() != chain().size()) {
    throw Error("manipulability gradient output has " + std::to_string(gradient.size()) +
                " entries, the chain to '" + chain().frame().name + "' has " +
                std::to_string(chain().size()) + " joints");
  }
  compute(q, true);
  compute_gradient(gradient);
  return result_;
}

void Manipulability::compute(const Eigen::Ref<const Eigen::VectorXd>& q, bool vectors) noexcept {
  kin_.update(q);
  kin_.jacobian(J_, JacobianFrame::world_aligned);
  J_block_ = J_.middleRows(first_row_, rows_);
  if (vectors) {
    svd_->vectors.compute(J_block_);
    sigma_ = svd_->vectors.singularValues();
  } else {
    svd_->values.compute(J_block_);
    sigma_ = svd_->values.singularValues();
  }
  const int p = static_cast<int>(sigma_.size());
  double w = 1.0;
  for (int k = 0; k < p; ++k) w *= sigma_[k];
  result_.manipulability = w;
  result_.sigma_max = sigma_[0];
  result_.sigma_min = sigma_[p - 1];
  const double ratio = result_.sigma_max > 0.0 ? result_.sigma_min / result_.sigma_max : 0.0;
  if (result_.sigma_max <= 0.0 || ratio <= options_.singular_tolerance) {
    result_.status = SingularityStatus::singular;
    result_.condition_number = std::numeric_limits<double>::infinity();
  } else {
    result_.status = ratio < options_.near_singular_threshold ? SingularityStatus::near_singular
                                                              : SingularityStatus::regular;
    result_.condition_number = result_.sigma_max / result_.sigma_min;
  }
}

void Manipulability::compute_gradient(Eigen::Ref<Eigen::VectorXd> gradient) noexcept {
  const int n = chain().size();
  if (result_.status == SingularityStatus::singular) {
    // w has a kink at an exact singularity: report no direction rather than a one-sided slope
    gradient.setZero();
    return;
  }
  // weights = U·diag(c)·Vᵀ with cofactors c_k = Π_{l≠k} σ_l (= w/σ_k without dividing), so that
  // ∂w/∂q_i = Σ_k c_k u_kᵀ ∂J_i v_k = Σ_j <∂J_i column j, weights column j>
  const int p = static_cast<int>(sigma_.size());
  const auto& U = svd_->vectors.matrixU();
  const auto& V = svd_->vectors.matrixV();
  weights_.setZero();
  for (int k = 0; k < p; ++k) {
    double c = 1.0;
    for (int l = 0; l < p; ++l) {
      if (l != k) c *= sigma_[l];
    }
    weights_.middleRows(first_row_, rows_).noalias() += c * U.col(k) * V.col(k).transpose();
  }
  for (int i = 0; i < n; ++i) {
    double g = 0.0;
    if (kin_.moves_frame(i)) {
      for (int j = 0; j < n; ++j) g += column_derivative(i, j).dot(weights_.col(j));
    }
    gradient[i] = g;
  }
}

Vector6d Manipulability::column_derivative(int i, int j) const noexcept {
  Vector6d d = Vector6d::Zero();
  if (!kin_.moves_frame(i) || !kin_.moves_frame(j)) return d;
  // on one path, the joint with the smaller model id is the proximal one (mujoco numbers joints
  // body by body, parents before children)
  if (joint_id_[i] < joint_id_[j]) {
    // joint i turns joint j's axis and lever arm rigidly: both columns rotate with ω_i
    if (hinge_[i]) {
      const Eigen::Vector3d& w = kin_.axis(i);
      d.head<3>() = w.cross(J_.col(j).head<3>());
      d.tail<3>() = w.cross(J_.col(j).tail<3>());
    }
  } else if (hinge_[j]) {
    // joint i (at or after j) only moves the frame point: ∂(a_j × (p − o_j)) = a_j × ∂p/∂q_i
    d.head<3>() = kin_.axis(j).cross(J_.col(i).head<3>());
  }
  return d;
}

void Manipulability::jacobian_derivative(int i, Eigen::Ref<Matrix6Xd> dJ) const {
  const int n = chain().size();
  if (i < 0 || i >= n || dJ.cols() != n) {
    throw Error("jacobian_derivative: joint index " + std::to_string(i) + " or output columns " +
                std::to_string(dJ.cols()) + " do not fit a chain of " + std::to_string(n) +
                " joints");
  }
  for (int j = 0; j < n; ++j) dJ.col(j) = column_derivative(i, j);
}

ManipulabilityResult manipulability(const Chain& chain, const Eigen::VectorXd& q,
                                    const ManipulabilityOptions& options) {
  Manipulability measure(chain, options);
  return measure.evaluate(q);
}

}  // namespace mjarm
