#pragma once
// Checks of controller options at construction (they throw; compute() never does) and the small
// state reads the task-space controllers share.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <string>

#include "mjarm/dynamics/chain_dynamics.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/chain.hpp"

namespace mjarm::detail {

/// The finger positions of one end of a gripper's stroke: @p given (one per finger joint), or
/// the joints' upper (@p upper) or lower limits when @p given is empty.
/// The values of @p given are checked by the caller (`check_fields`).
/// @throws Error "<owner>: <what> …" for a wrong count, or an infinite joint range with nothing
/// given.
inline Eigen::VectorXd finger_stroke_end(const Chain& chain, const Eigen::VectorXd& given,
                                         bool upper, const char* owner, const char* what) {
  const int n = chain.size();
  if (given.size() == n) return given;
  if (given.size() != 0) {
    throw Error(std::string(owner) + ": " + what + " needs " + std::to_string(n) +
                " entries (one per finger joint) or none, got " + std::to_string(given.size()));
  }
  const Eigen::VectorXd& limit = upper ? chain.upper() : chain.lower();
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(limit[i])) {
      throw Error(std::string(owner) + ": finger joint '" + chain.joint_names()[i] +
                  "' has no finite range; give open and closed");
    }
  }
  return limit;
}

/// "[a, b, c]" for error messages.
inline std::string values_text(const Eigen::Ref<const Eigen::VectorXd>& v) {
  std::ostringstream os;
  os << '[';
  for (Eigen::Index i = 0; i < v.size(); ++i) os << (i ? ", " : "") << v[i];
  os << ']';
  return os.str();
}

/// A copy of @p options whose entries past the first @p rows of each of @p members (6-vectors)
/// are set to 1: a position task ignores rows 3–5, so `check_fields` on the copy leaves them
/// unchecked (1 lies in every range those gains accept).
template <class Options, class... Members>
Options ignored_rows_cleared(Options options, int rows, Members... members) {
  ((options.*members).tail(6 - rows).setOnes(), ...);
  return options;
}

/// True when @p R is finite, orthonormal to 1e-6 and a proper rotation (det > 0).
inline bool is_rotation(const Eigen::Matrix3d& R) noexcept {
  if (!R.allFinite()) return false;
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return off <= 1e-6 && R.determinant() > 0.0;
}

/// True when everything @p dynamics read from the state is finite (q, q̇, M, h, J, J̇·q̇, the
/// velocity of E) and E's rotation is a rotation: a state a control law can run on.
inline bool state_valid(const ChainDynamics& dynamics) noexcept {
  return dynamics.q().allFinite() && dynamics.qd().allFinite() &&
         dynamics.mass_matrix().allFinite() && dynamics.bias().allFinite() &&
         dynamics.jacobian().allFinite() && dynamics.bias_acceleration().allFinite() &&
         dynamics.velocity().allFinite() && is_rotation(dynamics.pose().R);
}

/// The passive forces (joint damping, springs) on the chain's dofs, from qfrc_passive [N·m or N].
inline void read_passive(const Chain& chain, const mjData& d, Eigen::Ref<Eigen::VectorXd> out) noexcept {
  const auto& dofs = chain.dof_addresses();
  for (std::size_t i = 0; i < dofs.size(); ++i) out[static_cast<Eigen::Index>(i)] = d.qfrc_passive[dofs[i]];
}

}  // namespace mjarm::detail
