#include "mjarm/tasks/docking/scene.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

constexpr double kPlate = 0.010;  // bottom plate thickness [m]
constexpr std::array<double, 4> kSocketColor{0.35, 0.45, 0.6, 1.0};

void check_geometry(const DockingGeometry& g) {
  check_fields(g);
  if (!(g.bore_radius > g.peg_radius))
    throw Error("docking scene: the bore (radius " + number_text(g.bore_radius) +
                " m) must be wider than the peg (radius " + number_text(g.peg_radius) + " m)");
  if (!(g.peg_length > g.bore_depth + g.chamfer))
    throw Error("docking scene: the peg (" + number_text(g.peg_length) +
                " m) must be longer than the hole is deep (" +
                number_text(g.bore_depth + g.chamfer) + " m), or the flange hits the socket");
  check_value(g.solref[0], "docking scene", "solref[0] (time constant)", "s", Range::positive());
  check_value(g.solref[1], "docking scene", "solref[1] (damping ratio)", "", Range::positive());
  const auto& s = g.solimp;
  if (!(s[0] > 0.0 && s[0] < 1.0 && s[1] > 0.0 && s[1] < 1.0 && s[0] <= s[1]) || !(s[2] > 0.0) ||
      !std::isfinite(s[2]))
    throw Error("docking scene: solimp must be 0 < dmin ≤ dmax < 1 and width > 0");
}

std::array<double, 3> array_of(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

std::array<double, 4> quat_of(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return {q.w(), q.x(), q.y(), q.z()};
}

/// A piece of the socket at (R_SB, p_SB) in the socket's frame, its shape not set yet.
ObjectSpec socket_piece(const std::string& name, const Eigen::Matrix3d& R_SB,
                        const Eigen::Vector3d& p_SB, const DockingGeometry& g) {
  ObjectSpec piece;
  piece.name = name;
  piece.friction = {g.friction, 0.005, 0.0001};
  piece.pos = array_of(p_SB);
  piece.quat = quat_of(R_SB);
  piece.rgba = kSocketColor;
  return piece;
}

/// A box piece with half sizes @p half.
ObjectSpec box_piece(const std::string& name, const Eigen::Vector3d& p_SB,
                     const Eigen::Vector3d& half, const DockingGeometry& g) {
  ObjectSpec piece = socket_piece(name, Eigen::Matrix3d::Identity(), p_SB, g);
  piece.shape = ObjectShape::box;
  piece.size = {half.x(), half.y(), half.z()};
  return piece;
}

std::string two_digits(int k) { return (k < 10 ? "0" : "") + std::to_string(k); }

/// The socket's pieces in its own frame S: one convex piece per side of the polygon, the bottom
/// plate, the pedestal. A side's piece is the prism of its profile — bore wall from the plate up
/// to the chamfer's foot, the 45° chamfer up to the top face — so the edge where wall and chamfer
/// meet is an edge of one convex piece. As two boxes, the wall's top face met the chamfer box
/// there: a face inside the socket, on which the rim of a peg passing the foot caught (normal
/// straight up, docs/docking.md). The piece reaches down into the bottom plate, which buries its
/// lower face, and tangentially past the polygon's corners into its neighbours, which buries its
/// flanks.
std::vector<ObjectSpec> socket_pieces(const Pose& X_WS, const DockingGeometry& g) {
  std::vector<ObjectSpec> pieces;
  const double a = g.bore_radius;
  const double c = g.chamfer;
  const double outer = a + c + g.wall;
  const double bottom = -(c + g.bore_depth);  // the bottom plate's top face
  const double half_angle = std::numbers::pi / g.sides;
  const double half_width = outer * std::tan(half_angle);
  // the profile in (x outwards, z up): wall foot, chamfer foot, chamfer top, outer top, outer foot
  const double profile[5][2] = {
      {a, bottom - kPlate}, {a, -c}, {a + c, 0.0}, {outer, 0.0}, {outer, bottom - kPlate}};
  std::vector<double> vertices;
  for (const double y : {-half_width, half_width})
    for (const auto& [x, z] : profile) vertices.insert(vertices.end(), {x, y, z});
  for (int k = 0; k < g.sides; ++k) {
    const double theta = 2.0 * half_angle * k;
    ObjectSpec side =
        socket_piece("side_" + two_digits(k),
                     Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                     Eigen::Vector3d::Zero(), g);
    side.shape = ObjectShape::mesh;
    side.size.clear();
    side.mesh_vertices = vertices;
    pieces.push_back(std::move(side));
  }
  // bottom plate and the pedestal that carries it down to the floor
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  pieces.push_back(box_piece("bottom", (bottom - 0.5 * kPlate) * z,
                             Eigen::Vector3d(outer, outer, 0.5 * kPlate), g));
  const double pedestal = X_WS.p.z() + bottom - kPlate;  // its height
  if (pedestal > 1e-3)
    pieces.push_back(box_piece("pedestal", (bottom - kPlate - 0.5 * pedestal) * z,
                               Eigen::Vector3d(0.5 * outer, 0.5 * outer, 0.5 * pedestal), g));
  return pieces;
}

void add_socket(Scene& scene, const Pose& X_WS, const DockingGeometry& g) {
  CompoundFixtureSpec socket;
  socket.name = DockingNames::socket;
  socket.pos = array_of(X_WS.p);
  socket.quat = quat_of(X_WS.R);
  socket.pieces = socket_pieces(X_WS, g);
  scene.add_fixture(socket);
  for (const ObjectSpec& piece : socket.pieces) {
    const std::string geom = socket.name + "/" + piece.name;
    scene.set_attribute("geom", geom, "solref", g.solref);
    scene.set_attribute("geom", geom, "solimp", g.solimp);
  }
}

}  // namespace

void add_franka_joint_friction(Scene& scene, const std::string& robot) {
  for (std::size_t j = 0; j < kFrankaFrictionLoss.size(); ++j) {
    const double f[1] = {kFrankaFrictionLoss[j]};
    scene.set_attribute("joint", robot + "/joint" + std::to_string(j + 1), "frictionloss", f);
  }
}

Eigen::VectorXd iiwa14_max_velocity() {
  Eigen::VectorXd v(7);
  v << 85.0, 85.0, 100.0, 75.0, 130.0, 135.0, 135.0;
  return v * (std::numbers::pi / 180.0);
}

Scene docking_scene(const DockingSceneOptions& options) {
  const DockingGeometry& g = options.geometry;
  check_geometry(g);
  const Pose& X_WS = options.X_WS;
  if (!X_WS.p.allFinite() || !X_WS.R.allFinite() || !X_WS.R.isUnitary(1e-6) ||
      X_WS.R.determinant() < 0.0)
    throw Error("docking scene: the socket pose X_WS must be finite with a rotation matrix");
  if (X_WS.R(2, 2) < 1.0 - 1e-9)
    throw Error(
        "docking scene: the socket's axis z_S must point straight up (the pedestal stands "
        "on the floor); got z_S = (" +
        number_text(X_WS.R(0, 2)) + ", " + number_text(X_WS.R(1, 2)) + ", " +
        number_text(X_WS.R(2, 2)) + ")");
  if (X_WS.p.z() - (g.chamfer + g.bore_depth) - kPlate < 0.0)
    throw Error("docking scene: the socket's bottom would be below the floor (top at z = " +
                number_text(X_WS.p.z()) + " m)");

  Scene scene("docking");
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", g.ccd_tolerance);
  scene.set_option("ccd_tolerance", tolerance);
  scene.add_arena();
  scene.add_robot({DockingNames::robot, "iiwa14_torque", {0.0, 0.0, 0.0}, {1, 0, 0, 0}, false});
  scene.attach_gripper({DockingNames::robot, "docking_peg", "attachment_site", "peg"});
  // the peg's size and contact settings follow the geometry
  const std::string peg = DockingNames::peg_body;  // body and geom share the name
  const double half = 0.5 * g.peg_length;
  const double size[2] = {g.peg_radius, half};
  const double pos[3] = {0.0, 0.0, half};
  const double tip[3] = {0.0, 0.0, g.peg_length};
  scene.set_attribute("geom", peg, "size", size);
  scene.set_attribute("geom", peg, "pos", pos);
  scene.set_attribute("site", DockingNames::tip, "pos", tip);
  const double friction[3] = {g.friction, 0.005, 0.0001};
  scene.set_attribute("geom", peg, "friction", friction);
  scene.set_attribute("geom", peg, "solref", g.solref);
  scene.set_attribute("geom", peg, "solimp", g.solimp);
  // aluminium; MuJoCo takes the inertia of the solid cylinder from the geom
  const double mass[1] = {std::numbers::pi * g.peg_radius * g.peg_radius * g.peg_length * 2700.0};
  scene.set_attribute("geom", peg, "mass", mass);
  if (options.ft_sensor) {
    scene.add_sensor({DockingNames::force, SensorType::force, DockingNames::ft_site});
    scene.add_sensor({DockingNames::torque, SensorType::torque, DockingNames::ft_site});
  }
  if (options.joint_friction) add_franka_joint_friction(scene, DockingNames::robot);
  add_socket(scene, X_WS, g);
  return scene;
}

Pose DockingScene::seated() const { return seated(options.X_WS); }

Pose DockingScene::seated(const Pose& X_WS) const {
  const DockingGeometry& g = options.geometry;
  Pose X_SE;
  // R_y(π): the peg points down −z_S (x_E = −x_S: the iiwa's flange at its home keyframe)
  X_SE.R = Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal();
  X_SE.p = Eigen::Vector3d(0.0, 0.0, -(g.chamfer + g.bore_depth));
  return X_WS * X_SE;
}

DockingScene build_docking_scene(const DockingSceneOptions& options) {
  Robot robot = docking_scene(options).compile();
  Chain chain(robot, DockingNames::tip);
  DockingScene scene{.robot = robot,
                     .chain = chain,
                     .options = options,
                     .peg = GeomSet::of_bodies(robot, {DockingNames::peg_body}),
                     .socket = {}};
  scene.socket = GeomSet::of_bodies(robot, {DockingNames::socket});
  const mjModel& m = robot.model();
  scene.peg_body = robot.body(DockingNames::peg_body);
  scene.peg_mass = m.body_mass[scene.peg_body];
  // the peg's centre of mass in E, from the model at qpos0
  DataPtr d = robot.make_data();
  mj_forward(&m, d.get());
  const int tip = robot.site(DockingNames::tip);
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WE(d->site_xmat + 9 * tip);
  const Eigen::Map<const Eigen::Vector3d> p_WE(d->site_xpos + 3 * tip);
  const Eigen::Map<const Eigen::Vector3d> c_W(d->xipos + 3 * scene.peg_body);
  scene.peg_com_E = R_WE.transpose() * (c_W - p_WE);
  return scene;
}

bool same_geometry(const DockingGeometry& a, const DockingGeometry& b) noexcept {
  return a.peg_radius == b.peg_radius && a.peg_length == b.peg_length &&
         a.bore_radius == b.bore_radius && a.bore_depth == b.bore_depth && a.chamfer == b.chamfer &&
         a.sides == b.sides && a.wall == b.wall && a.friction == b.friction &&
         a.solref == b.solref && a.solimp == b.solimp && a.ccd_tolerance == b.ccd_tolerance;
}

std::shared_ptr<const DockingScene> shared_docking_scene(std::shared_ptr<const DockingScene> given,
                                                         bool joint_friction,
                                                         const DockingGeometry& geometry) {
  if (!given) {
    DockingSceneOptions options;
    options.joint_friction = joint_friction;
    options.geometry = geometry;
    return std::make_shared<const DockingScene>(build_docking_scene(options));
  }
  if (given->options.joint_friction != joint_friction)
    throw Error("docking: the scene given was built " +
                std::string(given->options.joint_friction ? "with" : "without") +
                " joint friction, the options ask for the other variant");
  if (!same_geometry(given->options.geometry, geometry))
    throw Error(
        "docking: the scene given was built for another peg or socket than the options "
        "ask for");
  return given;
}

}  // namespace mjarm
