#pragma once
/// @file
/// An arm from its Denavit–Hartenberg table: a chain of bodies written as MJCF (a joint per row,
/// a capsule along each link so it renders and collides, masses and inertias given or from the
/// capsules), loaded as a `Robot`. Standard (distal) and modified (Craig, proximal) conventions.
///
/// @code
/// DhArm arm;                                   // the UR5e's published table
/// arm.convention = DhConvention::standard;
/// arm.links = {{.d = 0.1625, .alpha = pi / 2}, {.a = -0.425}, {.a = -0.3922},
///              {.d = 0.1333, .alpha = pi / 2}, {.d = 0.0997, .alpha = -pi / 2}, {.d = 0.0996}};
/// const Robot ur5e = dh_robot(arm);            // joints joint1..6, end site "end"
/// @endcode

#include <Eigen/Core>
#include <array>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm {

/// Where a row's constant transform sits relative to its joint.
enum class DhConvention {
  standard,  ///< A_i = Rz(θ_i)·Tz(d_i)·Tx(a_i)·Rx(α_i): the joint at the start of the row
  modified   ///< T_i = Rx(α_i)·Tx(a_i)·Rz(θ_i)·Tz(d_i): α, a of the link before (Craig)
};

constexpr auto declared_names(const DhConvention*) {
  using E = DhConvention;
  return std::array{EnumName{E::standard, "standard", "A = Rz(θ) Tz(d) Tx(a) Rx(α)"},
                    EnumName{E::modified, "modified", "T = Rx(α) Tx(a) Rz(θ) Tz(d) (Craig)"}};
}

/// One row: the link's geometry, its joint and its mass.
struct DhLink {
  double a = 0.0;          ///< link length [m]
  double d = 0.0;          ///< link offset [m] (for a prismatic joint: added to the joint value)
  double alpha = 0.0;      ///< link twist [rad]
  double theta = 0.0;      ///< joint angle at zero joint value [rad] (for a revolute joint: added)
  bool prismatic = false;  ///< the joint slides along z instead of turning about it
  double lower = -std::numbers::pi;  ///< joint range [rad or m]
  double upper = std::numbers::pi;
  double mass = 1.0;  ///< [kg]
  /// Centre of mass in the link's body frame [m] and principal moments of inertia [kg·m²]; when
  /// not given, both come from the link's capsule at this mass.
  std::optional<Eigen::Vector3d> com{};
  std::optional<Eigen::Vector3d> inertia{};
};

constexpr auto declared_fields(const DhLink*) {
  using S = DhLink;
  return declare<S>(
      "DH link", field("a", &S::a, "m", Range::finite(), "link length"),
      field("d", &S::d, "m", Range::finite(), "link offset (prismatic: added to the joint value)"),
      field("alpha", &S::alpha, "rad", Range::finite(), "link twist"),
      field("theta", &S::theta, "rad", Range::finite(), "joint angle at zero (revolute: added)"),
      field("prismatic", &S::prismatic, "the joint slides along z instead of turning"),
      field("lower", &S::lower, "rad or m", Range::finite(), "joint range, lower end"),
      field("upper", &S::upper, "rad or m", Range::finite(), "joint range, upper end"),
      field("mass", &S::mass, "kg", Range::positive(), "link mass"),
      field("com", &S::com, "m", Range::finite(),
            "centre of mass in the link's frame; None: the capsule's"),
      field("inertia", &S::inertia, "kg·m²", Range::positive(),
            "principal moments of inertia; None: the capsule's"));
}

/// How the joints are driven.
enum class DhActuators {
  none,     ///< no actuators
  motor,    ///< a torque motor per joint (ctrl in N·m or N, ±effort)
  position  ///< a position servo per joint (ctrl: the target; kp = position_gain)
};

constexpr auto declared_names(const DhActuators*) {
  using E = DhActuators;
  return std::array{EnumName{E::none, "none"}, EnumName{E::motor, "motor"},
                    EnumName{E::position, "position"}};
}

/// An arm from a DH table.
struct DhArm {
  std::string name = "dh_arm";
  DhConvention convention = DhConvention::standard;
  std::vector<DhLink> links;
  /// The base frame in the world and the end site in the last row's frame, as 4×4 homogeneous
  /// transforms (rotation orthonormal).
  Eigen::Matrix4d base = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d tool = Eigen::Matrix4d::Identity();
  double radius = 0.03;  ///< the links' capsules [m]
  DhActuators actuators = DhActuators::motor;
  double effort = 100.0;         ///< motor limit [N·m or N]
  double position_gain = 500.0;  ///< servo kp
  double damping = 0.0;          ///< joint damping [N·m·s/rad or N·s/m]
  bool gravity = true;
};

constexpr auto declared_fields(const DhArm*) {
  using S = DhArm;
  return declare<S>(
      "DH arm", field("name", &S::name, "the model's name (letters, digits, _ and -)"),
      field("convention", &S::convention, "standard or modified DH"),
      field("radius", &S::radius, "m", Range::positive(), "the links' capsules"),
      field("actuators", &S::actuators, "how the joints are driven"),
      field("effort", &S::effort, "N·m or N", Range::positive(), "actuator force limit"),
      field("position_gain", &S::position_gain, "", Range::positive(), "position servo kp"),
      field("damping", &S::damping, "", Range::non_negative(), "joint damping"),
      field("gravity", &S::gravity, "gravity on (−9.81 m/s² along z)"));
}

/// The MJCF of @p arm: bodies link1..n (joints joint1..n), a site "end" at the tool frame, a
/// keyframe "zero". Numbers are written so they read back as the same doubles.
/// @throws Error for no rows, a non-finite or out-of-order value, a mass ≤ 0, a radius ≤ 0, a
///         base or tool that is not a rigid transform.
std::string dh_mjcf(const DhArm& arm);

/// `dh_mjcf` loaded.
/// @throws Error as `dh_mjcf`.
Robot dh_robot(const DhArm& arm);

}  // namespace mjarm
