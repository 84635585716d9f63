#pragma once
/// @file
/// The shortest duration of a joint-space quintic that keeps every joint within its velocity and
/// acceleration limits, found exactly (docs/trajectory.md, "Shortest quintic duration").

#include <Eigen/Core>

#include "mjarm/fields.hpp"
#include "mjarm/trajectory/quintic.hpp"

namespace mjarm {

/// How the search for the shortest quintic duration ended.
enum class QuinticDurationStatus {
  ok,                   ///< `duration` is the shortest feasible duration
  start_beyond_limits,  ///< a start velocity or acceleration is beyond its limit: no duration helps
  end_beyond_limits,    ///< an end velocity or acceleration is beyond its limit
  infeasible            ///< the limits hold at both ends but no duration keeps them in between
};

/// The names are spelled with spaces, as messages use them (Python: start_beyond_limits, …).
constexpr auto declared_names(const QuinticDurationStatus*) {
  using S = QuinticDurationStatus;
  return std::array{EnumName{S::ok, "ok", "the shortest feasible duration"},
                    EnumName{S::start_beyond_limits, "start beyond limits",
                             "a start velocity or acceleration is beyond its limit"},
                    EnumName{S::end_beyond_limits, "end beyond limits",
                             "an end velocity or acceleration is beyond its limit"},
                    EnumName{S::infeasible, "infeasible", "no duration keeps the limits"}};
}

/// The result of `shortest_quintic_duration`.
struct QuinticDuration {
  QuinticDurationStatus status = QuinticDurationStatus::infeasible;
  double duration = 0.0;             ///< the shortest feasible T [s] (when ok)
  Eigen::Index limiting_joint = -1;  ///< the joint whose limit is met at T (−1: none, T = floor)
  bool velocity_limited = false;     ///< true: its velocity limit is met; false: acceleration
};

/// The shortest T ≥ @p min_duration for which the quintic from @p start to @p end (any boundary
/// values) keeps |q̇_i(t)| ≤ v_max,i and |q̈_i(t)| ≤ a_max,i on all of [0, T] for every joint i.
///
/// Method (exact, no sampling of durations): with τ = t/T the quintic is
/// q(τ) = q₀ + A(τ) + T·B(τ) + T²·C(τ) with fixed polynomials A (from the displacement), B (from
/// the boundary velocities) and C (from the boundary accelerations), so each limit reads
/// g(τ, T) = A⁽ᵏ⁾(τ) + T·B⁽ᵏ⁾(τ) + T²·C⁽ᵏ⁾(τ) ∓ limit·Tᵏ ≤ 0 (k = 1 velocity, 2 acceleration).
/// Feasibility in T is not monotone in general, but the smallest feasible T is a duration at
/// which an interior extremum of some joint touches its limit: g = 0 and ∂g/∂τ = 0. Eliminating
/// T (the resultant of the two polynomials, quadratic in T) leaves a polynomial in τ whose real
/// roots in [0, 1] (eigenvalues of its companion matrix) give candidate T; each is polished by
/// Newton's method on (τ, T), and the smallest candidate at which every joint verifies its limits
/// (its exact peaks, to 1e-9 relative) is returned. The ends contribute no candidate: there v and
/// a equal the boundary values whatever T is.
///
/// @param start, end  boundary states (n entries each)
/// @param max_velocity      v_max (n entries, positive) [rad/s or m/s]
/// @param max_acceleration  a_max (n entries, positive) [rad/s² or m/s²]
/// @param min_duration      a floor on T [s], ≥ 0 (when 0 and nothing moves, T = 0)
/// @throws Error when sizes differ or are 0, a value is not finite, a limit is not positive, or
///         @p min_duration is negative.
QuinticDuration shortest_quintic_duration(const QuinticTrajectory::State& start,
                                          const QuinticTrajectory::State& end,
                                          const Eigen::VectorXd& max_velocity,
                                          const Eigen::VectorXd& max_acceleration,
                                          double min_duration = 0.0);

}  // namespace mjarm
