#pragma once
/// @file
/// The wiping scene: an iiwa14 in torque mode with a round-padded wiping tool at its flange (a
/// force/torque sensor pair between them) above a flat table (docs/scenarios.md).

#include <memory>

#include "mjarm/fields.hpp"
#include "mjarm/model/chain.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene.hpp"
#include "mjarm/sim/contact_query.hpp"

namespace mjarm {

/// The table and the tool's pad. Lengths in metres.
struct WipingSurface {
  double table_height = 0.2;  ///< the table's top face above the floor
  double friction = 0.3;      ///< sliding friction of pad and table (felt on a lacquered top)
  double pad_radius = 0.02;   ///< the round pad at the end of the tool
  /// Softness of the felt pad on the table: MuJoCo's solref time constant [s] (damping ratio 1).
  double pad_time_constant = 0.2;
  bool joint_friction = false;  ///< the Franka Panda's joint Coulomb friction on the iiwa14
};

constexpr auto declared_fields(const WipingSurface*) {
  using S = WipingSurface;
  return declare<S>(
      "wiping surface",
      field("table_height", &S::table_height, "m", Range::closed(0.05, 0.6),
            "the table's top face above the floor"),
      field("friction", &S::friction, "", Range::closed(0.0, 2.0),
            "sliding friction of pad and table"),
      field("pad_radius", &S::pad_radius, "m", Range::closed(0.005, 0.05),
            "radius of the tool's round pad"),
      field("pad_time_constant", &S::pad_time_constant, "s", Range::closed(0.004, 1.0),
            "softness of the felt pad: MuJoCo's solref time constant"),
      field("joint_friction", &S::joint_friction,
            "the Franka Panda's joint Coulomb friction on the iiwa14"));
}

/// The table's top face, in front of the robot: x from its near edge over its depth, y within
/// ± half its width [m].
inline constexpr double kWipingTableNear = 0.3;
inline constexpr double kWipingTableDepth = 0.5;
inline constexpr double kWipingTableWidth = 0.9;

/// Names in the wiping scene.
struct WipingNames {
  static constexpr const char* robot = "iiwa";
  static constexpr const char* tip = "iiwa/tool/tip";  ///< site: the controlled frame E
  static constexpr const char* ft_site = "iiwa/tool/ft";
  static constexpr const char* force = "iiwa/tool/ft_force";
  static constexpr const char* torque = "iiwa/tool/ft_torque";
  static constexpr const char* tool = "iiwa/tool/tool";  ///< the tool's body
  static constexpr const char* table = "table";          ///< the table: body, geom "table/geom"
};

/// The compiled wiping scene and what a run needs from it.
struct WipingScene {
  Robot robot;  ///< iiwa14 torque motors, tool, table, floor
  Chain chain;  ///< iiwa joints 1–7, frame: the pad's tip
  WipingSurface surface;
  GeomSet tool{};   ///< the tool's geoms
  GeomSet arm{};    ///< the robot's geoms but the tool's
  GeomSet table{};  ///< the table's geom
};

/// The parts of the wiping scene, not compiled: arena, iiwa14_torque, the tool
/// (models/grippers/wiping_tool.xml) at `attachment_site` with its F/T sensors, the table (a box
/// from the floor to `table_height`, its top as the constants above say);
/// elliptic friction cones, pad and table as soft as `pad_time_constant` says.
/// @throws Error for a value of @p surface out of its range.
Scene wiping_scene(const WipingSurface& surface = {});

/// True when @p a and @p b build the same scene (every field).
bool same_surface(const WipingSurface& a, const WipingSurface& b) noexcept;

/// Compiles `wiping_scene(surface)` and looks up its names.
/// @throws Error as `wiping_scene`, or when the scene does not compile.
WipingScene build_wiping_scene(const WipingSurface& surface = {});

}  // namespace mjarm
