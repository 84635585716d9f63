#pragma once
/// @file
/// `Scene`: one MuJoCo model composed of parts — an arena, robots from any MJCF, grippers
/// attached to their flanges, free objects, fixtures, cameras, sites, sensors and welds — with
/// every part's names prefixed, found and edited by name, then compiled into a `Robot`.
///
/// The scene is an `mjSpec` (MuJoCo's model-editing API): each MJCF part is parsed from its staged
/// file (`parse_mjcf_file`) and attached with `mjs_attach` under its prefix, so MuJoCo itself
/// prefixes names and references and keeps each part's compiler settings (angle unit, euler
/// sequence), default classes and assets; what the scene makes itself (arena, objects, cameras,
/// sites, sensors, welds) is added element by element.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene_spec.hpp"

namespace mjarm {

/// A composed scene. Every `add_*` checks its spec and every name it brings, and leaves the
/// scene unchanged when it throws. Copies are independent (edit a copy per trial).
class Scene {
 public:
  /// An empty scene (no floor: see `add_arena`) called @p name.
  explicit Scene(std::string name = "scene");
  ~Scene();
  Scene(const Scene& other);
  Scene& operator=(const Scene& other);
  Scene(Scene&& other) noexcept;
  Scene& operator=(Scene&& other) noexcept;

  /// Adds the floor, two lights and, when asked, the table (names in `ArenaSpec`).
  /// @throws Error for a bad value or when an arena is already there.
  void add_arena(const ArenaSpec& arena = {});

  /// Adds a robot; its names get the prefix `spec.name + "/"`. Global settings (option, size,
  /// visual) it sets are taken where the scene has none; see `warnings()`.
  /// @throws Error for an unknown bundled name (with the closest ones), a missing, invalid or
  ///         non-MJCF file, a robot name used twice, a name clash, or a global setting MuJoCo
  ///         refuses to merge (an integrator, cone, gravity, ... other than the scene's).
  void add_robot(const RobotSpec& spec);

  /// Attaches a gripper rigidly at a site or body of a robot already in the scene.
  /// @throws Error for an unknown robot, an unknown frame (naming the robot's sites and bodies
  ///         closest to it), or an unknown gripper (with the bundled grippers).
  void attach_gripper(const GripperSpec& spec);

  /// Adds a free object (a body with a free joint: nq += 7, nv += 6).
  /// @throws Error for a bad size, mass, friction or pose, a missing mesh file, or a name clash.
  void add_object(const ObjectSpec& spec);
  /// Adds a fixture: an object fixed to the world (no joint).
  void add_fixture(const ObjectSpec& spec);
  /// Adds a fixture of several pieces in one static body (see `CompoundFixtureSpec`).
  /// @throws Error for a bad piece (named), a piece name used twice, no pieces, a missing mesh
  ///         file, or a name clash.
  void add_fixture(const CompoundFixtureSpec& spec);
  /// Adds a camera. @throws Error for an unknown parent or target body or a name clash.
  void add_camera(const SceneCameraSpec& spec);
  /// Adds a site. @throws Error for an unknown parent body or a name clash.
  void add_site(const SiteSpec& spec);
  /// Adds a sensor. @throws Error when its target does not exist (with the closest names).
  void add_sensor(const SensorSpec& spec);
  /// Adds a weld equality. @throws Error when a body does not exist (with the closest names).
  void add_weld(const WeldSpec& spec);
  /// Adds any element by its MJCF tag and attributes (`ElementSpec`), checked when added: the
  /// tag, the name (free in the scene), the parent body or class, the default class, every
  /// attribute's name (closest names), kind and count. MuJoCo judges the rest (a negative size,
  /// a sensor without its object) when the scene is compiled.
  /// @throws Error naming the element and what is wrong; the scene is unchanged.
  void add(const ElementSpec& element);

  /// Whether an element of @p kind ("body", "joint", "geom", "site", "camera", "light",
  /// "actuator", "sensor", "tendon", "equality", "mesh", "material", "texture", "default") is
  /// called @p name.
  bool has(std::string_view kind, std::string_view name) const;
  /// Names of the elements of @p kind, sorted.
  std::vector<std::string> names(std::string_view kind) const;

  /// Value of MJCF attribute @p attribute of element @p name as text (numbers in their shortest
  /// round-trip form): what the element holds, written in its file, inherited from its default
  /// class or MuJoCo's default; nullopt where it holds none (an empty reference, an orientation
  /// written another way, an unset fromto).
  /// @throws Error when the element does not exist (with the closest names) or has no such
  ///         attribute (with the closest attribute names).
  std::optional<std::string> attribute(std::string_view kind, std::string_view name,
                                       std::string_view attribute) const;
  /// Sets an MJCF attribute of an element ("size", "pos", "euler", "gainprm", "range",
  /// "ctrlrange", "solreflimit", "type", "material", ...); takes effect at the next `compile()`.
  /// Fewer numbers than the attribute holds set the leading ones where MJCF allows it (size,
  /// friction, gainprm, solimp, gear, ...). Angles are in the unit of the part the element came
  /// from (its compiler's angle). Renaming is refused (names are checked on add), and so is a
  /// default class (it applies when an element is made).
  /// @throws Error when the element or the attribute does not exist (closest names), or for a
  ///         value of the wrong kind or count or an unknown keyword; MuJoCo judges the rest
  ///         (a negative size, ...) when the scene is compiled.
  void set_attribute(std::string_view kind, std::string_view name, std::string_view attribute,
                     std::string_view value);
  /// Sets a numeric attribute. @throws Error as above, or when a value is not finite.
  void set_attribute(std::string_view kind, std::string_view name, std::string_view attribute,
                     std::span<const double> values);

  /// Sets a global simulation option, `<option ATTRIBUTE="VALUE">` (timestep, impratio,
  /// noslip_iterations, cone, integrator, ...); it wins over what parts set, before or after.
  /// @throws Error for an unknown attribute (closest names) or a value of the wrong kind.
  void set_option(std::string_view attribute, std::string_view value);

  /// The scene as one MJCF document, as MuJoCo writes its spec (`mj_saveXMLString`, values as
  /// written: every number exact, angles in radians, absolute asset paths), with the combined
  /// keyframes; it loads into the same model as `compile()` gives.
  /// @throws Error as `compile()`, or with MuJoCo's message when it cannot write the spec.
  std::string xml() const;

  /// Compiles a copy of the scene's spec (the scene itself is unchanged).
  /// Keyframes of the parts are combined by name: the scene's key `home` holds every part's
  /// `home` values; joints of parts without it keep qpos0, actuators 0.
  /// @throws Error "scene 'NAME' does not compile: " with MuJoCo's message.
  Robot compile() const;

  /// The scene's name (its model name once compiled).
  const std::string& name() const noexcept;
  /// Messages about the parts: MuJoCo's parser warnings, and its word on global settings a part
  /// brought (taken because the scene had none, or merged with the scene's: the smaller
  /// timestep, the larger iteration counts, ...).
  const std::vector<std::string>& warnings() const noexcept;

  /// Names of the bundled grippers (files in `Robot::models_dir() / "grippers"`), sorted.
  static std::vector<std::string> bundled_grippers();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjarm
