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
#include <string>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// One active contact, in world coordinates.
struct ContactForce {
  int geom1 = -1;
  int geom2 = -1;
  int body1 = -1;  ///< body of geom1 (0 = world)
  int body2 = -1;  ///< body of geom2
  std::string geom1_name{}, geom2_name{}, body1_name{}, body2_name{};  ///< "" when unnamed
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< contact point, world [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< unit normal, geom1 → geom2, world
  /// The contact frame, world: rows are the normal and the two tangent directions
  /// (`mjContact::frame`).
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  double distance = 0.0;  ///< signed distance between the geoms; negative: penetration [m]
  /// Force exerted by geom1 on geom2, world axes [N]: f_W = Cᵀ·f_C with C = mjContact::frame
  /// (rows = contact axes) and f_C = first three values of mj_contactForce.
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();
  double normal_force = 0.0;  ///< its normal component f_C[0] (≥ 0: contacts push) [N]
  /// Its tangential part (friction), world axes [N]: force_W − normal_force·normal.
  Eigen::Vector3d friction_W = Eigen::Vector3d::Zero();
  /// Torsional and rolling torque exerted by geom1 on geom2 about the contact point, world axes
  /// [N·m] (zero unless the contact has condim 4 or 6).
  Eigen::Vector3d torque_W = Eigen::Vector3d::Zero();
};

constexpr auto declared_fields(const ContactForce*) {
  using S = ContactForce;
  return declare<S>(
      "contact", field("geom1", &S::geom1, "", "geom id"), field("geom2", &S::geom2, "", "geom id"),
      field("body1", &S::body1, "", "body of geom1 (0: world)"),
      field("body2", &S::body2, "", "body of geom2"),
      field("geom1_name", &S::geom1_name, "'' when unnamed"),
      field("geom2_name", &S::geom2_name, "'' when unnamed"),
      field("body1_name", &S::body1_name, "'world' for body 0"),
      field("body2_name", &S::body2_name, "'' when unnamed"),
      field("position", &S::position, "m", "contact point, world"),
      field("normal", &S::normal, "", "unit normal from geom1 to geom2, world"),
      field("distance", &S::distance, "m", "signed distance; negative: penetration"),
      field("force_W", &S::force_W, "N", "force of geom1 on geom2, world axes"),
      field("normal_force", &S::normal_force, "N", "its normal component (≥ 0)"),
      field("friction_W", &S::friction_W, "N", "its tangential part (friction), world axes"),
      field("torque_W", &S::torque_W, "N·m",
            "torsional and rolling torque of geom1 on geom2, world axes"));
}

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

/// Every active contact of @p d (exclude = 0 and a constraint row in efc), in d.contact order,
/// with the geoms' and bodies' names.
/// @p d must hold constraint forces, i.e. come after `mj_forward` or `mj_step`.
std::vector<ContactForce> contact_forces(const mjModel& m, const mjData& d);

/// Sums @p contacts per body pair, ordered so that body1 < body2 (a contact listed the other
/// way round is added with its sign flipped). Pairs appear in the order first met.
std::vector<BodyPairForce> sum_by_body_pair(const std::vector<ContactForce>& contacts);

/// Total contact force exerted on @p body by the other bodies, world axes [N]: +force_W where
/// @p body is body2, −force_W where it is body1 (contacts of a body with itself cancel).
Eigen::Vector3d contact_force_on_body(const std::vector<ContactForce>& contacts, int body);

}  // namespace mjarm
