#pragma once
/// @file
/// The docking scene: an iiwa14 in torque mode with a cylindrical peg at its flange (a
/// force/torque sensor pair between them) above a fixed socket built from convex pieces — a
/// polygonal bore with a chamfered entry — on a pedestal (docs/docking.md).

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mjarm/fields.hpp"
#include "mjarm/lie/pose.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene.hpp"
#include "mjarm/sim/contact_query.hpp"

namespace mjarm {

/// Sizes and contact settings of the peg and the socket. Lengths in metres.
struct DockingGeometry {
  double peg_radius = 0.015;    ///< Ø30 mm peg
  double peg_length = 0.100;    ///< from the flange to the end face
  double bore_radius = 0.0155;  ///< Ø31 mm bore: 0.5 mm radial clearance
  double bore_depth = 0.040;    ///< straight part of the hole, below the chamfer
  /// 45° chamfer at the entry: radial width = height. The hole opens to
  /// bore_radius + chamfer at the top face.
  double chamfer = 0.010;
  /// The bore and the chamfer are regular polygons of this many faces (≥ 8), each side of the
  /// hole — wall and chamfer — one convex piece (MuJoCo collides a mesh through its convex hull,
  /// so a hole must be made of convex pieces). The faces are tangent to the bore's circle: the
  /// clearance is 0.5 mm at the middle of a face and bore_radius/cos(π/sides) − peg_radius at a
  /// corner (0.58 mm for 32 faces).
  int sides = 32;
  double wall = 0.010;    ///< radial thickness of the socket beyond the chamfer's top edge
  double friction = 0.3;  ///< sliding friction of peg and socket (steel on aluminium, dry)
  /// Contact softness (MuJoCo solref: time constant [s], damping ratio) of peg and socket.
  std::array<double, 2> solref{0.01, 1.0};
  /// MuJoCo solimp of peg and socket (dmin, dmax, width [m]): MuJoCo's default. A stiffer
  /// impedance (0.95, 0.99) leaves the seated peg a few micrometres deep, where it loses and
  /// regains contact ten times a second under the preload.
  std::array<double, 3> solimp{0.9, 0.95, 0.001};
  /// Tolerance of MuJoCo's convex collision (GJK/EPA, option `ccd_tolerance`) [m]. A contact
  /// shallower than it may come back with its normal reversed; where the peg touches two pieces
  /// at once (the chamfer's foot, the walls beside a pressed wall) it then faces the other
  /// piece's contact and the pair brakes the sliding peg like a clamp (up to 89 N at MuJoCo's
  /// default, 1 µm). Contacts here begin anywhere from 0 to about 40 µm deep (a step's travel)
  /// and the seated preload holds the peg 0.1 µm deep, so the tolerance sits far below both
  /// (docs/docking.md).
  double ccd_tolerance = 1e-12;
};

/// Checked with the scene (`solref`, `solimp` and the sizes relative to each other by hand).
constexpr auto declared_fields(const DockingGeometry*) {
  using S = DockingGeometry;
  return declare<S>(
      "docking scene",
      field("peg_radius", &S::peg_radius, "m", Range::positive(), "radius of the peg"),
      field("peg_length", &S::peg_length, "m", Range::positive(),
            "from the flange to the end face"),
      field("bore_radius", &S::bore_radius, "m", Range::positive(),
            "radius of the bore's inscribed circle"),
      field("bore_depth", &S::bore_depth, "m", Range::positive(),
            "straight part of the hole, below the chamfer"),
      field("chamfer", &S::chamfer, "m", Range::positive(), "45° chamfer at the entry"),
      field("sides", &S::sides, "", Range::closed(8, 256), "faces of the polygonal bore"),
      field("wall", &S::wall, "m", Range::positive(),
            "radial thickness of the socket beyond the chamfer"),
      field("friction", &S::friction, "", Range::non_negative(),
            "sliding friction of peg and socket"),
      field("ccd_tolerance", &S::ccd_tolerance, "m", Range::positive(),
            "tolerance of MuJoCo's convex collision"));
}

/// The Franka Emika Panda's identified joint Coulomb friction [N·m] (the --friction variant puts
/// it on the iiwa14's joints 1–7).
inline constexpr std::array<double, 7> kFrankaFrictionLoss{1.137, 1.137, 1.137, 1.137,
                                                           0.763, 0.44,  0.248};

/// Puts `kFrankaFrictionLoss` on joints 1–7 of the iiwa14 called @p robot in @p scene (its joints
/// `ROBOT/joint1` … `ROBOT/joint7`): the friction variant of the docking and the wiping.
void add_franka_joint_friction(Scene& scene, const std::string& robot);

/// The iiwa14's joint speed limits (KUKA LBR iiwa 14 R820 datasheet: 85, 85, 100, 75, 130, 135,
/// 135 °/s) [rad/s].
Eigen::VectorXd iiwa14_max_velocity();

/// How to build the scene.
struct DockingSceneOptions {
  DockingGeometry geometry;
  /// Pose of the socket frame S in the world: origin at the centre of the hole's top opening,
  /// z out of the hole (the peg goes in along −z_S).
  Pose X_WS{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.6, 0.0, 0.2)};
  /// Add the force/torque sensor pair at the flange (site `iiwa/peg/ft`). Without it, only the
  /// sensorless (momentum observer) force source works.
  bool ft_sensor = true;
  /// The variant with joint friction: frictionloss `kFrankaFrictionLoss` on joints 1–7 (the
  /// model's joint damping, 1 ×4 and 0.5 ×3 N·m·s/rad, is there in both variants).
  bool joint_friction = false;
};

/// `X_WS` is bound by hand (a pose); the rest as declared.
constexpr auto declared_fields(const DockingSceneOptions*) {
  using S = DockingSceneOptions;
  return declare<S>(
      "docking scene options", field("geometry", &S::geometry, "the peg and the socket"),
      field("ft_sensor", &S::ft_sensor, "the F/T sensor pair at the flange"),
      field("joint_friction", &S::joint_friction, "the Franka joint friction on joints 1–7"));
}

/// Names in the docking scene.
struct DockingNames {
  static constexpr const char* robot = "iiwa";
  static constexpr const char* tip = "iiwa/peg/tip";           ///< site: the controlled frame E
  static constexpr const char* ft_site = "iiwa/peg/ft";        ///< site of the F/T sensor pair
  static constexpr const char* force = "iiwa/peg/ft_force";    ///< force sensor
  static constexpr const char* torque = "iiwa/peg/ft_torque";  ///< torque sensor
  static constexpr const char* peg_body = "iiwa/peg/peg";      ///< the peg's body
  /// The socket: one static body; its geoms `socket/side_NN` (wall and chamfer of a side, a
  /// convex mesh), `socket/bottom`, `socket/pedestal`.
  static constexpr const char* socket = "socket";
};

/// The compiled docking scene and what a run needs from it.
struct DockingScene {
  Robot robot;  ///< the composed model (iiwa14 torque motors, peg, socket, floor)
  Chain chain;  ///< iiwa joints 1–7, frame: the peg tip site
  DockingSceneOptions options;
  GeomSet peg;            ///< the peg's geoms
  GeomSet socket;         ///< the socket's pieces (bore, chamfer, bottom, pedestal)
  int peg_body = -1;      ///< body id of the peg
  double peg_mass = 0.0;  ///< [kg] (the F/T sensor carries it)
  Eigen::Vector3d peg_com_E = Eigen::Vector3d::Zero();  ///< peg's centre of mass in E [m]
  /// Pose of E (the tip) seated at the bottom of the hole: X_WS · (R_y(π), −(chamfer +
  /// bore_depth)·z_S).
  Pose seated() const;
  /// The same for a socket at @p X_WS.
  Pose seated(const Pose& X_WS) const;
};

/// The parts of the docking scene, not compiled: arena, iiwa14_torque, the peg
/// (models/grippers/docking_peg.xml) at `attachment_site`, the F/T sensors, the socket pieces
/// and the pedestal, the joint friction of the variant.
/// @throws Error when a size is not positive and finite, the clearance is not positive, the
///         number of sides is below 8, the contact settings are out of MuJoCo's ranges, or
///         the socket is below the floor.
Scene docking_scene(const DockingSceneOptions& options = {});

/// Compiles `docking_scene(options)` and looks up its names.
/// @throws Error as `docking_scene`, or when the scene does not compile.
DockingScene build_docking_scene(const DockingSceneOptions& options = {});

/// True when @p a and @p b build the same peg and socket (every field, solref and solimp too).
bool same_geometry(const DockingGeometry& a, const DockingGeometry& b) noexcept;

/// @p given when set (it must be the @p joint_friction variant of @p geometry), else a new scene
/// of that variant: the scene a run shares or builds.
/// @throws Error when @p given is another variant or geometry, or as `build_docking_scene`.
std::shared_ptr<const DockingScene> shared_docking_scene(std::shared_ptr<const DockingScene> given,
                                                         bool joint_friction,
                                                         const DockingGeometry& geometry = {});

}  // namespace mjarm
