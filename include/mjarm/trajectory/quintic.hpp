#pragma once
/// @file
/// Quintic polynomials with arbitrary boundary conditions: `Quintic` (one coordinate) and
/// `QuinticTrajectory` (n joints sharing one duration).

#include <Eigen/Core>
#include <array>

#include "mjarm/trajectory/trajectory_sample.hpp"

namespace mjarm {

/// The quintic p(t) = Σ c_k t^k, t ∈ [0, T], that meets position, velocity and acceleration at
/// both ends (docs/trajectory.md). With h = p₁ − p₀:
///
///     c₀ = p₀, c₁ = v₀, c₂ = a₀/2,
///     c₃ = (20h − (8v₁ + 12v₀)T − (3a₀ − a₁)T²)/(2T³),
///     c₄ = (−30h + (14v₁ + 16v₀)T + (3a₀ − 2a₁)T²)/(2T⁴),
///     c₅ = (12h − 6(v₁ + v₀)T + (a₁ − a₀)T²)/(2T⁵).
///
/// Units: p in u, v in u/s, a in u/s², jerk in u/s³.
class Quintic {
 public:
  /// Position, velocity and acceleration at one end.
  struct State {
    double p = 0.0;  ///< position [u]
    double v = 0.0;  ///< velocity [u/s]
    double a = 0.0;  ///< acceleration [u/s²]
  };

  /// Position, velocity, acceleration and jerk at one instant.
  struct Sample {
    double p = 0.0;  ///< [u]
    double v = 0.0;  ///< [u/s]
    double a = 0.0;  ///< [u/s²]
    double j = 0.0;  ///< [u/s³]
  };

  /// The peaks of |v|, |a| and |j| over [0, T], found exactly at the roots of the next
  /// derivative and at the ends.
  struct Peaks {
    double velocity = 0.0;      ///< max |v| [u/s]
    double acceleration = 0.0;  ///< max |a| [u/s²]
    double jerk = 0.0;          ///< max |j| [u/s³]
  };

  /// The quintic from @p start to @p end in @p duration [s]. A zero duration is accepted only
  /// when positions and velocities agree (then it is a step of acceleration at t = 0).
  /// @throws Error when a boundary value is not finite or the duration is negative, not finite,
  ///         or zero between different states.
  Quintic(const State& start, const State& end, double duration);

  /// The duration T [s].
  double duration() const noexcept { return duration_; }
  /// The coefficients c₀ … c₅ in powers of t [s].
  const std::array<double, 6>& coefficients() const noexcept { return c_; }

  /// The sample at @p t [s]; t is clamped to [0, T] (NaN gives the start), and the jerk is 0
  /// outside [0, T].
  Sample at(double t) const noexcept;
  /// One coordinate (a `TrajectoryProfile` of dofs() = 1).
  int dofs() const noexcept { return 1; }
  /// `at(t)` as a `TrajectorySample` of one coordinate.
  void at(double t, TrajectorySample& sample) const;

  /// Exact peaks of |v|, |a|, |j| over [0, T].
  Peaks peaks() const;

 private:
  std::array<double, 6> c_{};
  double duration_;
};

/// n quintics sharing one duration: joint-space motion from any (q, q̇, q̈) to any (q, q̇, q̈).
/// The blending case — a start in motion, an end at rest — is `QuinticTrajectory::to_rest`.
class QuinticTrajectory {
 public:
  /// Joint positions, velocities and accelerations (n each, chain order).
  struct State {
    Eigen::VectorXd q;    ///< [rad or m]
    Eigen::VectorXd qd;   ///< [rad/s or m/s]
    Eigen::VectorXd qdd;  ///< [rad/s² or m/s²]
  };

  /// From @p start to @p end in @p duration [s].
  /// @throws Error when the sizes differ or are 0, a value is not finite, or the duration is
  ///         invalid for a joint (see `Quintic`; the joint is named).
  QuinticTrajectory(const State& start, const State& end, double duration);

  /// From @p start (possibly moving) to rest at @p goal in @p duration [s].
  /// @throws Error as the constructor.
  static QuinticTrajectory to_rest(const State& start, const Eigen::VectorXd& goal,
                                   double duration);

  /// The number of joints n.
  Eigen::Index size() const noexcept { return coefficients_.rows(); }
  /// The number of joints n (as a `TrajectoryProfile`).
  Eigen::Index dofs() const noexcept { return coefficients_.rows(); }
  /// The duration T [s].
  double duration() const noexcept { return duration_; }
  /// Joint @p i's quintic.
  /// @throws Error when @p i is out of range.
  Quintic joint(Eigen::Index i) const;

  /// q, q̇, q̈ at @p t [s] (clamped to [0, T]); allocates nothing.
  /// @throws Error when an output does not have n entries.
  void at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
          Eigen::Ref<Eigen::VectorXd> qdd) const;

  /// q, q̇, q̈ and the jerk q⃛ at @p t [s] (clamped; jerk 0 outside [0, T]); allocates nothing.
  /// @throws Error when an output does not have n entries.
  void at(double t, Eigen::Ref<Eigen::VectorXd> q, Eigen::Ref<Eigen::VectorXd> qd,
          Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::VectorXd> qddd) const;
  /// q, q̇, q̈, q⃛ at @p t [s] into @p sample (resized to n when it is not); allocates nothing
  /// once it is.
  void at(double t, TrajectorySample& sample) const;

 private:
  Eigen::Matrix<double, Eigen::Dynamic, 6> coefficients_;  // row i: joint i's c₀ … c₅
  double duration_;
};

}  // namespace mjarm
