#pragma once
/// @file
/// What a scene is made of: plain descriptions of an arena, robots, grippers, objects, cameras,
/// sites, sensors and welds, checked by `validate()` before they are composed (see `Scene`).
/// Each declares its fields (fields.hpp: the Python properties and their docs); `validate()`
/// checks the declared ranges in its own words (with MuJoCo's magnitude bound, the sizes a shape
/// takes and the checks that relate fields).

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Floor, lights and an optional table. Names: `arena/floor`, `arena/table` (body),
/// `arena/table_top` (geom), `arena/table_surface` (site at the centre of the top surface).
struct ArenaSpec {
  std::array<double, 2> floor_half_size{2.0, 2.0};           ///< plane half extents x, y [m]
  bool table = false;                                        ///< add a table
  std::array<double, 2> table_center{0.5, 0.0};              ///< table centre x, y in world [m]
  std::array<double, 2> table_half_size{0.4, 0.6};           ///< top half extents x, y [m]
  double table_height = 0.4;                                 ///< height of the top surface [m]
  std::array<double, 3> table_friction{1.0, 0.005, 0.0001};  ///< sliding, torsional, rolling
};

constexpr auto declared_fields(const ArenaSpec*) {
  using S = ArenaSpec;
  return declare<S>(
      "arena",
      field("floor_half_size", &S::floor_half_size, "m", Range::positive(),
            "floor plane half extents x, y"),
      field("table", &S::table, "add a table"),
      field("table_center", &S::table_center, "m", Range::finite(), "table centre x, y in world"),
      field("table_half_size", &S::table_half_size, "m", Range::positive(),
            "table top half extents x, y"),
      field("table_height", &S::table_height, "m", Range{0.05, Range::inf, true, false, false},
            "height of the top surface"),
      field("table_friction", &S::table_friction, "", Range::non_negative(),
            "sliding, torsional, rolling"));
}

/// A robot from any MJCF: a bundled name ("arm6", "panda_hand", ...) or a file path (URDF is not
/// attached: convert it to MJCF first). Every name in it gets the prefix `name + "/"`
/// ("left/joint1"); the robot's root bodies go inside a fixed body called `name` placed at `pos`,
/// `quat` in world.
struct RobotSpec {
  std::string name;                                ///< prefix, unique in the scene
  std::string model;                               ///< bundled name or MJCF file path
  std::array<double, 3> pos{0.0, 0.0, 0.0};        ///< mount position in world [m]
  std::array<double, 4> quat{1.0, 0.0, 0.0, 0.0};  ///< mount orientation (w, x, y, z)
  /// Keep the model's own floor planes, lights and skybox (bundled models include them).
  bool keep_arena = false;
};

constexpr auto declared_fields(const RobotSpec*) {
  using S = RobotSpec;
  return declare<S>("robot", field("name", &S::name, "prefix, unique in the scene"),
                    field("model", &S::model, "bundled name or MJCF file path"),
                    field("pos", &S::pos, "m", Range::finite(), "mount position in world"),
                    field("quat", &S::quat, "", Range::finite(), "mount orientation w, x, y, z"),
                    field("keep_arena", &S::keep_arena,
                          "keep the model's own floor planes, lights and skybox"));
}

/// A gripper MJCF attached rigidly to a robot frame (no joint is added between them: the
/// scene's nq grows by the gripper's own joints only). Names get the prefix
/// `robot + "/" + name + "/"`; the gripper's root bodies go inside a body `robot/name` placed at
/// the frame.
struct GripperSpec {
  std::string robot;             ///< name of a robot already in the scene
  std::string model;             ///< bundled gripper name ("franka_hand") or MJCF file path
  std::string frame;             ///< site or body of the robot, unprefixed ("attachment_site")
  std::string name = "gripper";  ///< prefix inside the robot's
};

constexpr auto declared_fields(const GripperSpec*) {
  using S = GripperSpec;
  return declare<S>("gripper", field("robot", &S::robot, "a robot already in the scene"),
                    field("model", &S::model, "bundled gripper name or MJCF file path"),
                    field("frame", &S::frame, "site or body of the robot, unprefixed"),
                    field("name", &S::name, "prefix inside the robot's"));
}

/// Shapes of objects and fixtures.
enum class ObjectShape { box, sphere, cylinder, capsule, mesh };

constexpr auto declared_names(const ObjectShape*) {
  using O = ObjectShape;
  return std::array{EnumName{O::box, "box", "size: 3 half extents"},
                    EnumName{O::sphere, "sphere", "size: radius"},
                    EnumName{O::cylinder, "cylinder", "size: radius, half length"},
                    EnumName{O::capsule, "capsule", "size: radius, half length of the cylinder"},
                    EnumName{O::mesh, "mesh", "the convex hull of a mesh file or of vertices"}};
}

/// The shape called @p name (`parse_enum` with the kind "object shape").
/// @throws Error "unknown object shape 'cub'; closest: box; object shapes: box, …"
ObjectShape object_shape(std::string_view name);

/// A rigid object: free (`Scene::add_object`, adds a free joint: nq += 7, nv += 6) or fixed to
/// the world (`Scene::add_fixture`). Names: body `name`, geom `name/geom`, site `name/center`,
/// free joint `name/joint`, mesh asset `name/mesh`.
struct ObjectSpec {
  std::string name;
  ObjectShape shape = ObjectShape::box;
  /// box: 3 half extents; sphere: radius; cylinder and capsule: radius, half length [m];
  /// mesh: 3 scale factors (or empty for 1 1 1).
  std::vector<double> size{0.02, 0.02, 0.02};
  std::string mesh_file;                               ///< STL/OBJ/MSH file, for shape mesh
  /// For shape mesh instead of a file: the vertices, x y z in the object's frame [m] (at least
  /// 4 points, not all in one plane); MuJoCo collides and weighs their convex hull.
  std::vector<double> mesh_vertices;
  double mass = 0.1;                                   ///< [kg], > 0
  std::array<double, 3> friction{1.0, 0.005, 0.0001};  ///< sliding, torsional, rolling, >= 0
  std::array<double, 3> pos{0.0, 0.0, 0.0};            ///< position in world [m]
  std::array<double, 4> quat{1.0, 0.0, 0.0, 0.0};      ///< orientation in world (w, x, y, z)
  std::array<double, 4> rgba{0.8, 0.3, 0.2, 1.0};
};

constexpr auto declared_fields(const ObjectSpec*) {
  using S = ObjectSpec;
  return declare<S>(
      "object", field("name", &S::name, "unique in the scene"),
      field("shape", &S::shape, "box, sphere, cylinder, capsule or mesh"),
      field("size", &S::size, "m", Range::positive(),
            "box: 3 half extents; sphere: radius; cylinder, capsule: radius, half length; mesh: 3 "
            "scale factors or none"),
      field("mesh_file", &S::mesh_file, "STL/OBJ/MSH file, for shape mesh"),
      field("mesh_vertices", &S::mesh_vertices, "m", Range::finite(),
            "for shape mesh instead of a file: x y z of at least 4 points, not in one plane"),
      field("mass", &S::mass, "kg", Range::positive(), "mass"),
      field("friction", &S::friction, "", Range::non_negative(), "sliding, torsional, rolling"),
      field("pos", &S::pos, "m", Range::finite(), "position in world"),
      field("quat", &S::quat, "", Range::finite(), "orientation in world w, x, y, z"),
      field("rgba", &S::rgba, "", Range::closed(0.0, 1.0), "colour"));
}

/// A fixture made of several pieces in one static body: a hollow part (a socket, a bin) has to
/// be built from convex pieces, since MuJoCo collides a mesh through its convex hull. One body
/// instead of one per piece also keeps MuJoCo's broad phase from pairing the pieces with each
/// other at every step. Names: body `name`, geoms `name/<piece name>`, site `name/center`.
struct CompoundFixtureSpec {
  std::string name;
  std::array<double, 3> pos{0.0, 0.0, 0.0};        ///< position of the body in world [m]
  std::array<double, 4> quat{1.0, 0.0, 0.0, 0.0};  ///< orientation in world (w, x, y, z)
  /// The pieces: each one's `pos` and `quat` are in the fixture's frame; `mass` is not used
  /// (the body is static); names are unique within the fixture.
  std::vector<ObjectSpec> pieces;
};

/// The pieces are not declared: each is an `ObjectSpec`, checked as one.
constexpr auto declared_fields(const CompoundFixtureSpec*) {
  using S = CompoundFixtureSpec;
  return declare<S>("fixture", field("name", &S::name, "unique in the scene"),
                    field("pos", &S::pos, "m", Range::finite(), "position of the body in world"),
                    field("quat", &S::quat, "", Range::finite(), "orientation w, x, y, z"));
}

/// A camera fixed to a body (or the world), optionally tracking a body.
struct SceneCameraSpec {
  std::string name;
  std::string body;                          ///< parent body, empty for the world
  std::array<double, 3> pos{0.0, 0.0, 0.0};  ///< in the parent body [m]
  /// x and y axes of the image in the parent body (the camera looks along −z), not parallel;
  /// all zero to use `quat` instead (giving both is an error).
  std::array<double, 6> xyaxes{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  std::array<double, 4> quat{1.0, 0.0, 0.0, 0.0};
  double fovy = 45.0;  ///< vertical field of view [deg]
  std::string target;  ///< body to look at (mode targetbody), or empty
};

constexpr auto declared_fields(const SceneCameraSpec*) {
  using S = SceneCameraSpec;
  return declare<S>(
      "camera", field("name", &S::name, "unique in the scene"),
      field("body", &S::body, "parent body, empty for the world"),
      field("pos", &S::pos, "m", Range::finite(), "position in the parent body"),
      field("xyaxes", &S::xyaxes, "", Range::finite(),
            "image x and y axes in the parent body, not parallel; all zero: use quat"),
      field("quat", &S::quat, "", Range::finite(), "orientation w, x, y, z"),
      field("fovy", &S::fovy, "deg", Range{0.0, 180.0, true, true, false},
            "vertical field of view"),
      field("target", &S::target, "body to look at, or empty"));
}

/// A site on a body (or the world).
struct SiteSpec {
  std::string name;
  std::string body;                          ///< parent body, empty for the world
  std::array<double, 3> pos{0.0, 0.0, 0.0};  ///< in the parent body [m]
  std::array<double, 4> quat{1.0, 0.0, 0.0, 0.0};
  double size = 0.005;  ///< sphere radius [m]
  std::array<double, 4> rgba{0.2, 0.8, 0.2, 1.0};
};

constexpr auto declared_fields(const SiteSpec*) {
  using S = SiteSpec;
  return declare<S>("site", field("name", &S::name, "unique in the scene"),
                    field("body", &S::body, "parent body, empty for the world"),
                    field("pos", &S::pos, "m", Range::finite(), "position in the parent body"),
                    field("quat", &S::quat, "", Range::finite(), "orientation w, x, y, z"),
                    field("size", &S::size, "m", Range::positive(), "sphere radius"),
                    field("rgba", &S::rgba, "", Range::closed(0.0, 1.0), "colour"));
}

/// Sensor types a scene can add.
enum class SensorType { jointpos, framepos, framequat, touch, force, torque };

constexpr auto declared_names(const SensorType*) {
  using T = SensorType;
  return std::array{EnumName{T::jointpos, "jointpos", "a joint's position [rad or m]"},
                    EnumName{T::framepos, "framepos", "a frame's position in world [m]"},
                    EnumName{T::framequat, "framequat", "a frame's orientation w, x, y, z"},
                    EnumName{T::touch, "touch", "normal contact force in a site's volume [N]"},
                    EnumName{T::force, "force", "force at a site, in its frame [N]"},
                    EnumName{T::torque, "torque", "torque at a site, in its frame [N·m]"}};
}

/// The sensor type called @p name (`parse_enum` with the kind "sensor type").
/// @throws Error "unknown sensor type 'frampos'; closest: framepos; sensor types: …"
SensorType sensor_type(std::string_view name);

/// A sensor on a named element: a joint (jointpos), a site (touch, force, torque) or a site,
/// body, geom or camera (framepos, framequat; a body's frame, not its centre of mass).
struct SensorSpec {
  std::string name;
  SensorType type = SensorType::framepos;
  std::string target;
};

constexpr auto declared_fields(const SensorSpec*) {
  using S = SensorSpec;
  return declare<S>("sensor", field("name", &S::name, "unique in the scene"),
                    field("type", &S::type, "what it measures"),
                    field("target", &S::target, "the element it reads"));
}

/// A weld equality between two bodies (e.g. a gripper body and an object), declared inactive
/// unless @p active: the grasp switches it on.
struct WeldSpec {
  std::string name;
  std::string body1;  ///< e.g. "arm/hand"
  std::string body2;  ///< e.g. "cube"
  bool active = false;
  std::array<double, 2> solref{0.002, 1.0};  ///< time constant [s], damping ratio
};

constexpr auto declared_fields(const WeldSpec*) {
  using S = WeldSpec;
  return declare<S>("weld", field("name", &S::name, "unique in the scene"),
                    field("body1", &S::body1, "e.g. 'arm/hand'"),
                    field("body2", &S::body2, "e.g. 'cube'"),
                    field("active", &S::active, "on from the start"),
                    field("solref", &S::solref, "", Range::positive(),
                          "time constant [s], damping ratio"));
}

/// Any element, by its MJCF tag and attributes: what `Scene::add` makes (the job of dm_control's
/// `mjcf.RootElement`, on the scene's spec). Tags:
/// - in a body (`parent`: the body, "" for the world): body, joint, geom, site, camera, light;
/// - actuators: general, motor, position (attributes kp, kv), velocity (kv), with the
///   transmission as in MJCF (joint, jointinparent, tendon, site, body);
/// - sensors: jointpos, jointvel, actuatorpos, actuatorvel, actuatorfrc, framepos, framequat,
///   framexaxis, frameyaxis, framezaxis, framelinvel, frameangvel, framelinacc, frameangacc,
///   touch, force, torque, accelerometer, velocimeter, gyro, magnetometer, subtreecom,
///   subtreelinvel, subtreeangmom, clock; the object as in MJCF (joint, actuator, site, body, or
///   objtype + objname, reftype + refname);
/// - default: a default class (`parent`: its parent class, "" for main); its attributes are
///   "<element>.<attribute>" ("geom.rgba", "joint.damping", "position.kp" is written
///   "actuator.gainprm").
struct ElementSpec {
  std::string tag;
  std::string name;        ///< unique in the scene among its kind (a default: the class name)
  std::string parent;      ///< the parent body, or a default's parent class ("" = world / main)
  std::string class_name;  ///< the default class the element starts from ("" = its parent's)
  /// MJCF attributes, applied in order: numbers separated by spaces, keywords, names.
  std::vector<std::pair<std::string, std::string>> attributes;
};

/// Checks sizes, masses, frictions, frames (a zero or non-finite quaternion, a camera's zero or
/// parallel axes) and names of a spec.
/// @throws Error naming the spec and the bad value with what was expected.
void validate(const RobotSpec& spec);
void validate(const GripperSpec& spec);
void validate(const ObjectSpec& spec);
void validate(const CompoundFixtureSpec& spec);
void validate(const SceneCameraSpec& spec);
void validate(const SiteSpec& spec);
void validate(const WeldSpec& spec);
void validate(const ArenaSpec& spec);

}  // namespace mjarm
