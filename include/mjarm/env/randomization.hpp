#pragma once
/// @file
/// Domain randomization: masses, friction, damping, actuator gains and object sizes, scaled by
/// factors drawn from an episode's random state and written into a simulation's own model copy.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/random.hpp"

namespace mjarm {

/// Relative ranges r of the randomized parameters: each element is multiplied by a factor drawn
/// uniformly from [1 − r, 1 + r]. 0 leaves the parameter at its nominal value. Each r in [0, 1).
struct RandomizationOptions {
  double mass = 0.0;      ///< every body's mass and rotational inertia (one factor per body)
  double friction = 0.0;  ///< every geom's friction coefficients (one factor per geom)
  double damping = 0.0;   ///< every dof's joint damping (one factor per dof)
  double gain = 0.0;  ///< every actuator's gain (one factor per actuator; a position servo's kp and
                      ///< kv together)
  double object_size =
      0.0;  ///< the task's object geoms: size × s, mass × s³, inertia × s⁵ (density kept)

  /// True when any range is non-zero.
  bool any() const noexcept;
  /// @throws Error naming the first range that is not in [0, 1).
  void check() const;
};

constexpr auto declared_fields(const RandomizationOptions*) {
  using S = RandomizationOptions;
  constexpr Range kRelative{0.0, 1.0, false, true, false};  // [0, 1)
  return declare<S>(
      "randomization",
      field("mass", &S::mass, "", kRelative, "body masses and inertias (one factor per body)"),
      field("friction", &S::friction, "", kRelative, "geom friction (one factor per geom)"),
      field("damping", &S::damping, "", kRelative, "joint damping (one factor per dof)"),
      field("gain", &S::gain, "", kRelative, "actuator gains (one factor per actuator)"),
      field("object_size", &S::object_size, "", kRelative,
            "the task's object geoms (size, mass, inertia)"));
}

/// Applies `RandomizationOptions` to a model copy. Each `apply` first restores the nominal
/// values (so the draws never compound), then draws, in this order and only for the non-zero
/// ranges: one factor per body (1 … nbody−1), per geom, per dof, per actuator, per object geom;
/// then recomputes the model's derived constants (`mj_setConst`: subtree masses, the inertia
/// the constraint solver scales with). An object geom's bounding radius is scaled with it, so
/// collision detection sees the new size. The actuator binding of a simulation keeps the
/// nominal gain: a gain factor g makes a motor deliver g times the commanded torque.
class DomainRandomizer {
 public:
  /// @param nominal the model as loaded (kept by reference: it must outlive the randomizer)
  /// @param object_geoms geom ids the object-size range applies to
  /// @throws Error for ranges out of [0, 1), an object geom id out of range, or an object-size
  ///         range with no object geoms.
  DomainRandomizer(const mjModel& nominal, const RandomizationOptions& options,
                   std::vector<int> object_geoms);

  const RandomizationOptions& options() const noexcept { return options_; }

  /// Restores @p model (a copy of the nominal model, same sizes) to the nominal values, draws
  /// new factors from @p rng and writes them; @p scratch is overwritten by `mj_setConst`.
  /// Allocation-free.
  void apply(mjModel& model, mjData& scratch, Random& rng) noexcept;

  /// Factors of the last `apply` (empty for a range of 0): per body (nbody, body 0 = 1), per
  /// geom, per dof, per actuator, per object geom.
  const Eigen::VectorXd& mass_factors() const noexcept { return mass_; }
  const Eigen::VectorXd& friction_factors() const noexcept { return friction_; }
  const Eigen::VectorXd& damping_factors() const noexcept { return damping_; }
  const Eigen::VectorXd& gain_factors() const noexcept { return gain_; }
  const Eigen::VectorXd& size_factors() const noexcept { return size_; }
  const std::vector<int>& object_geoms() const noexcept { return objects_; }

 private:
  const mjModel& nominal_;
  RandomizationOptions options_;
  std::vector<int> objects_;
  Eigen::VectorXd mass_, friction_, damping_, gain_, size_;
};

}  // namespace mjarm
