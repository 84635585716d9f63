#pragma once
/// @file
/// World-frame contact forces read from an `mjData`, per contact and summed per body pair.
///
/// Sign convention (MuJoCo's): each contact's frame has its normal (first row of
/// `mjContact::frame`) pointing from geom1 towards geom2, and the constraint force that
/// `mj_contactForce` returns in that frame is the force geom1 exerts on geom2 (a positive normal
/// component pushes geom2 away from geom1). geom2 therefore exerts −force on geom1. MuJoCo itself
/// books it that way when it accumulates `cfrc_ext` (body of geom2 gets +f, body of geom1 −f).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <vector>

namespace mjarm {

/// One active contact, in world coordinates.
struct ContactForce {
  int geom1 = -1;
  int geom2 = -1;
  int body1 = -1;                                      ///< body of geom1 (0 = world)
  int body2 = -1;                                      ///< body of geom2
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< contact point, world [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< unit normal, geom1 → geom2, world
  /// Force exerted by geom1 on geom2, world axes [N]: f_W = Cᵀ·f_C with C = mjContact::frame
  /// (rows = contact axes) and f_C = first three values of mj_contactForce.
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  /// Torsional and rolling torque exerted by geom1 on geom2 about the contact point, world axes
  /// [N·m] (zero unless the contact has condim 4 or 6).
  Eigen::Vector3d torque_W = Eigen::Vector3d::Zero();
};

/// Forces of all contacts between one pair of bodies (body1 < body2).
struct BodyPairForce {
  int body1 = -1;
  int body2 = -1;
  int contacts = 0;  ///< number of contacts summed
  /// Sum of the forces exerted by body1 on body2, world axes [N].
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  /// Sum of the contact torques (about each contact's own point, not r × f) by body1 on body2,
  /// world axes [N·m].
  Eigen::Vector3d torque_W = Eigen::Vector3d::Zero();
};

/// Every active contact of @p d (exclude = 0 and a constraint row in efc), in d.contact order.
/// @p d must hold constraint forces, i.e. come after `mj_forward` or `mj_step`.
std::vector<ContactForce> contact_forces(const mjModel& m, const mjData& d);

/// Sums @p contacts per body pair, ordered so that body1 < body2 (a contact listed the other
/// way round is added with its sign flipped). Pairs appear in the order first met.
std::vector<BodyPairForce> sum_by_body_pair(const std::vector<ContactForce>& contacts);

/// Total contact force exerted on @p body by the other bodies, world axes [N]: +force_W where
/// @p body is body2, −force_W where it is body1 (contacts of a body with itself cancel).
Eigen::Vector3d contact_force_on_body(const std::vector<ContactForce>& contacts, int body);

}  // namespace mjarm
