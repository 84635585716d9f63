#pragma once
/// @file
/// Contact queries between two sets of geoms: "is the robot touching the table", "how hard do
/// the fingers press on the object". Allocation-free, so a task can ask every tick.
///
/// Sign convention as in kinematics/contacts.hpp (MuJoCo's): the force a contact reports is the
/// one geom1 exerts on geom2; a query between sets A and B reports the force A exerts on B.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mjarm/model/robot.hpp"

namespace mjarm {

/// A set of geoms of one model (a membership mask over geom ids).
class GeomSet {
 public:
  /// The empty set.
  GeomSet() = default;

  /// The geoms of the bodies called @p bodies ("world" names body 0, which holds the floor),
  /// with every body below them when @p subtree is true.
  /// @throws Error naming an unknown body (with close names).
  static GeomSet of_bodies(const Robot& robot, const std::vector<std::string>& bodies,
                           bool subtree = true);

  /// The geoms called @p geoms.
  /// @throws Error naming an unknown geom.
  static GeomSet of_geoms(const Robot& robot, const std::vector<std::string>& geoms);

  /// Every geom of the model not in this set.
  /// @pre the set was built for @p robot (or is empty)
  GeomSet complement(const Robot& robot) const;

  /// Adds the geoms of @p other (same model).
  GeomSet& add(const GeomSet& other);

  /// True when geom id @p geom belongs to the set.
  bool contains(int geom) const noexcept {
    return geom >= 0 && geom < static_cast<int>(mask_.size()) && mask_[geom] != 0;
  }
  /// Number of geoms in the set.
  int size() const noexcept;
  /// True when the set holds no geom.
  bool empty() const noexcept { return size() == 0; }

 private:
  std::vector<std::uint8_t> mask_;  // 1 per geom id of the model; sized ngeom once non-empty
};

/// Contacts between two geom sets A and B, summed. Forces are in world axes.
struct ContactSummary {
  int contacts = 0;  ///< active contacts between A and B (within the geoms' margins)
  /// Smallest signed distance of those contacts [m]; negative = penetration. +inf when none.
  double min_distance = std::numeric_limits<double>::infinity();
  /// Sum of the forces A exerts on B, world axes [N]. Zero when `forces_valid` is false.
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  /// Sum of the normal components of those forces [N] (≥ 0: contacts push, never pull).
  double normal_force = 0.0;
  /// False when the data held no constraint forces (kinematic mode): only the contact count and
  /// distances are meaningful then.
  bool forces_valid = true;
  /// Geom ids of the first contact found (geom of A, geom of B), −1 when none.
  int first_geom_a = -1;
  int first_geom_b = -1;
};

/// Sums the contacts of @p d between a geom of @p a and a geom of @p b (an empty @p b means
/// any geom outside @p a). Allocates nothing.
/// @p d must hold consistent contacts and constraint forces (after mj_forward or mj_step2) when
/// @p with_forces is true; otherwise only counts and distances are read.
ContactSummary contact_between(const mjModel& m, const mjData& d, const GeomSet& a,
                               const GeomSet& b, bool with_forces = true) noexcept;

}  // namespace mjarm
