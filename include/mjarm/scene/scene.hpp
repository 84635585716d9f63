#pragma once
/// @file
/// `Scene`: one MuJoCo model composed of parts — an arena, robots from any MJCF, grippers
/// attached to their flanges, free objects, fixtures, cameras, sites, sensors and welds — with
/// every part's names prefixed, found and edited by name, then compiled into a `Robot`.
///
/// MuJoCo 2.2.2 has neither `<attach>` nor a model-editing API: the scene works on the MJCF
/// itself. Each part is loaded as the model room loads it (MuJoCo 3.x translated, asset paths
/// absolute), normalized (angles in radians, euler and axis-angle orientations as quaternions,
/// following the part's own compiler settings) and prefixed before it is merged, so parts keep
/// their own units, default classes and asset folders.

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

  /// Adds a robot; its names get the prefix `spec.name + "/"`.
  /// @throws Error for an unknown bundled name (with the closest ones), a missing, invalid or
  ///         non-MJCF file, a robot name used twice, or a compiler setting that clashes with
  ///         another part.
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

  /// Whether an element of @p kind ("body", "joint", "geom", "site", "camera", "light",
  /// "actuator", "sensor", "tendon", "equality", "mesh", "material", "texture", "default") is
  /// called @p name.
  bool has(std::string_view kind, std::string_view name) const;
  /// Names of the elements of @p kind, sorted.
  std::vector<std::string> names(std::string_view kind) const;

  /// Value of attribute @p attribute of element @p name, or nullopt when it is not set there.
  /// @throws Error when the element does not exist (with the closest names).
  std::optional<std::string> attribute(std::string_view kind, std::string_view name,
                                       std::string_view attribute) const;
  /// Sets an attribute of an element ("size", "pos", "gainprm", "range", "ctrlrange", ...);
  /// takes effect at the next `compile()`. Renaming is refused (names are checked on add).
  /// @throws Error when the element does not exist or @p attribute is "name"; MuJoCo checks the
  ///         value when the scene is compiled.
  void set_attribute(std::string_view kind, std::string_view name, std::string_view attribute,
                     std::string_view value);
  /// Sets a numeric attribute. @throws Error as above, or when a value is not finite.
  void set_attribute(std::string_view kind, std::string_view name, std::string_view attribute,
                     std::span<const double> values);

  /// Sets a global simulation option, `<option ATTRIBUTE="VALUE">` (timestep, impratio,
  /// noslip_iterations, cone, ...), over whatever a part set. MuJoCo checks the value at the next
  /// `compile()`.
  /// @throws Error for an empty attribute name.
  void set_option(std::string_view attribute, std::string_view value);

  /// The composed MJCF document (MuJoCo 2.2.2, radians, absolute asset paths).
  std::string xml() const;

  /// Compiles the scene. Keyframes of the parts are combined by name: the scene's key `home`
  /// holds every part's `home` values; joints of parts without it keep qpos0, actuators 0.
  /// @throws Error with MuJoCo's message when the model does not compile.
  Robot compile() const;

  /// The scene's name (its model name once compiled).
  const std::string& name() const noexcept;
  /// Messages about the parts: 3.x translation rewrites and global settings of a part that the
  /// scene did not take because an earlier part set them otherwise.
  const std::vector<std::string>& warnings() const noexcept;

  /// Names of the bundled grippers (files in `Robot::models_dir() / "grippers"`), sorted.
  static std::vector<std::string> bundled_grippers();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjarm
