#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mjarm/dynamics/force_torque_sensor.hpp"
#include "mjarm/ik/pose_ik.hpp"
#include "mjarm/sim/contact_query.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "support/error_message.hpp"
#include "tasks/docking_test_support.hpp"

namespace mjarm {
namespace {

using test::contains;
using test::error_of;
using test::kDockingDeg;

TEST(DockingScene, ComposesTheArmThePegTheSensorAndTheSocket) {
  const DockingScene scene = build_docking_scene();
  const Robot& robot = scene.robot;
  const mjModel& m = robot.model();
  const DockingGeometry& g = scene.options.geometry;
  EXPECT_EQ(m.nq, 7);
  EXPECT_EQ(m.nu, 7);
  EXPECT_EQ(scene.chain.size(), 7);
  EXPECT_EQ(scene.chain.frame().name, DockingNames::tip);
  // the pieces: one per side (wall and chamfer), the bottom plate and the pedestal, one body
  EXPECT_EQ(scene.socket.size(), g.sides + 2);
  EXPECT_EQ(scene.peg.size(), 1);
  // an aluminium cylinder Ø30 × 100 mm
  EXPECT_NEAR(scene.peg_mass, std::numbers::pi * 0.015 * 0.015 * 0.1 * 2700.0, 1e-9);
  EXPECT_NEAR(scene.peg_com_E.z(), -0.05, 1e-12);
  EXPECT_NEAR(scene.peg_com_E.head<2>().norm(), 0.0, 1e-12);
  // the F/T pair sits on the flange site of the peg's own body
  const ForceTorqueSensor sensor(robot, DockingNames::ft_site);
  EXPECT_EQ(m.site_bodyid[sensor.site_id()], scene.peg_body);
  // gravity on, torque motors clipped at the iiwa's limits
  EXPECT_DOUBLE_EQ(m.opt.gravity[2], -9.81);
  EXPECT_DOUBLE_EQ(m.actuator_ctrlrange[2 * 5 + 1], 40.0);
  for (int j = 0; j < 7; ++j) EXPECT_DOUBLE_EQ(m.dof_frictionloss[j], 0.0);
  EXPECT_DOUBLE_EQ(m.opt.ccd_tolerance, g.ccd_tolerance);  // the scene's, not MuJoCo's 1e-6
}

TEST(DockingScene, TheBoreIsAPolygonTangentToItsCircleAndTheChamferOpensAt45Degrees) {
  const DockingScene scene = build_docking_scene();
  const Robot& robot = scene.robot;
  const mjModel& m = robot.model();
  const DockingGeometry& g = scene.options.geometry;
  DataPtr d = robot.make_data();
  mj_forward(&m, d.get());
  const Eigen::Vector3d p_S = scene.options.X_WS.p;
  const double a = g.bore_radius, c = g.chamfer;
  for (int k = 0; k < g.sides; ++k) {
    const std::string n = (k < 10 ? "0" : "") + std::to_string(k);
    const int side = robot.geom("socket/side_" + n);
    ASSERT_EQ(m.geom_type[side], mjGEOM_MESH);
    const double angle = 2.0 * std::numbers::pi * k / g.sides;
    const Eigen::Vector3d out(std::cos(angle), std::sin(angle), 0.0);
    // the vertices in S: the inner ones on the wall's face (radius a, down from the chamfer's
    // foot) and on the chamfer's top edge (a + c at the top face), none inside the hole
    const int mesh = m.geom_dataid[side];
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R(d->geom_xmat + 9 * side);
    const Eigen::Map<const Eigen::Vector3d> p(d->geom_xpos + 3 * side);
    int foot = 0, top = 0;
    for (int v = 0; v < m.mesh_vertnum[mesh]; ++v) {
      const float* f = m.mesh_vert + 3 * (m.mesh_vertadr[mesh] + v);
      const Eigen::Vector3d r = p + R * Eigen::Vector3d(f[0], f[1], f[2]) - p_S;
      const double radial = r.dot(out);
      EXPECT_GE(radial, std::max(a, a + c + r.z()) - 1e-6) << n;  // float vertices
      if (std::abs(radial - a) < 1e-6 && std::abs(r.z() + c) < 1e-6) ++foot;
      if (std::abs(radial - a - c) < 1e-6 && std::abs(r.z()) < 1e-6) ++top;
    }
    EXPECT_EQ(foot, 2) << n;  // the wall meets the 45° chamfer at the foot, on both flanks
    EXPECT_EQ(top, 2) << n;
  }
  // the peg seated on the bottom, centred: it touches nothing but the bottom plate
  const Pose X = scene.seated();
  PoseIk ik(scene.chain);
  Eigen::VectorXd seed(7);
  seed << 0.0, 0.8, 0.0, -1.5, 0.0, 0.83, 0.0;
  const IkResult r = ik.solve(Pose{X.R, X.p + Eigen::Vector3d(0.0, 0.0, 0.2e-3)}, seed);
  ASSERT_EQ(r.status, IkStatus::converged);
  scene.chain.scatter(r.q, d->qpos);
  mj_forward(&m, d.get());
  EXPECT_EQ(contact_between(m, *d, scene.peg, scene.socket, false).contacts, 0);
  // 0.45 mm sideways still clears the walls; 0.6 mm does not (0.5 mm clearance)
  for (const auto& [shift, touches] : {std::pair{0.45e-3, false}, std::pair{0.6e-3, true}}) {
    const IkResult s = ik.solve(Pose{X.R, X.p + Eigen::Vector3d(shift, 0.0, 5e-3)}, r.q);
    ASSERT_EQ(s.status, IkStatus::converged);
    scene.chain.scatter(s.q, d->qpos);
    mj_forward(&m, d.get());
    EXPECT_EQ(contact_between(m, *d, scene.peg, scene.socket, false).contacts > 0, touches)
        << shift;
  }
}

// The peg micrometres into the socket where it touches two pieces at once: its side against the
// foot of the chamfer, its rim just past the foot, and its side pressed into one wall until it
// reaches the two walls beside it (their tangent points are 11.25° away: 9.8 µm further). Every
// contact deeper than 1 nm must push the peg towards the axis (from a wall) or up and in (from
// the chamfer). Two faults pushed it otherwise (docs/docking.md): MuJoCo's GJK/EPA at its
// default tolerance (1 µm) returned sub-micrometre contacts with their normals reversed, and,
// when wall and chamfer were two boxes, the rim caught on the wall box's top face inside the
// socket (normal straight up).
TEST(DockingScene, ContactsWhereThePegTouchesTwoPiecesPushItInwards) {
  struct Placement {
    double depth;  // of the tip below the top face [m]
    double into;   // of the peg's side into the wall, beyond the clearance [m]
  };
  std::vector<Placement> foot, beside;
  for (const double depth : {0.012, 0.015, 0.021})  // the side against the foot
    for (int k = 1; k <= 40; ++k) foot.push_back({depth, k * 0.05e-6});
  for (const double past : {1e-6, 2e-6, 4e-6})  // the rim just below the foot
    for (int k = 1; k <= 10; ++k) foot.push_back({0.010 + past, k * 1e-6});
  for (const double depth : {0.015, 0.030})  // the side against three walls
    for (int k = 0; k < 40; ++k) beside.push_back({depth, 9.3e-6 + k * 0.05e-6});
  // the number of contacts pushing the peg the wrong way
  const auto wrong_normals = [](double ccd_tolerance, const std::vector<Placement>& placements,
                                int& checked) {
    DockingSceneOptions options;
    options.geometry.ccd_tolerance = ccd_tolerance;
    const DockingGeometry& g = options.geometry;
    const DockingScene scene = build_docking_scene(options);
    const mjModel& m = scene.robot.model();
    DataPtr d = scene.robot.make_data();
    PoseIkOptions ik_options;
    ik_options.position_tolerance = 1e-11;
    ik_options.orientation_tolerance = 1e-11;
    PoseIk ik(scene.chain, ik_options);
    Eigen::VectorXd q(7);
    q << 0.0, 0.8, 0.0, -1.5, 0.0, 0.83, 0.0;
    const Pose seated = scene.seated();
    const double clearance = g.bore_radius - g.peg_radius;
    int wrong = 0;
    checked = 0;
    for (const int face : {0, 8, 16, 24}) {
      const double angle = 2.0 * std::numbers::pi * face / g.sides;
      const Eigen::Vector3d out(std::cos(angle), std::sin(angle), 0.0);  // away from the axis
      for (const Placement& at : placements) {
        const Eigen::Vector3d p = scene.options.X_WS.p + (clearance + at.into) * out -
                                  at.depth * Eigen::Vector3d::UnitZ();
        const IkResult r = ik.solve(Pose{seated.R, p}, q);
        EXPECT_EQ(r.status, IkStatus::converged) << face << " " << at.depth << " " << at.into;
        q = r.q;
        scene.chain.scatter(q, d->qpos);
        mj_forward(&m, d.get());
        for (int c = 0; c < d->ncon; ++c) {
          const mjContact& con = d->contact[c];
          if (con.dist > -1e-9) continue;
          const double sign = scene.peg.contains(con.geom1) ? 1.0 : -1.0;  // peg → socket
          const Eigen::Vector3d n =
              sign * Eigen::Vector3d(con.frame[0], con.frame[1], con.frame[2]);
          ++checked;
          if (n.dot(out) < 0.5) ++wrong;  // wall: ≥ 0.99, chamfer: 0.71
        }
      }
    }
    return wrong;
  };
  const double tolerance = DockingGeometry{}.ccd_tolerance;
  int checked = 0;
  EXPECT_EQ(wrong_normals(tolerance, foot, checked), 0);
  EXPECT_GT(checked, static_cast<int>(4 * foot.size()));  // the wall and the chamfer
  EXPECT_EQ(wrong_normals(tolerance, beside, checked), 0);
  // four faces, and the walls beside reached in about half of the placements
  EXPECT_GT(checked, static_cast<int>(6 * beside.size()));
  // MuJoCo's default tolerance gets some of them backwards: what the setting is for
  EXPECT_GT(wrong_normals(1e-6, foot, checked), 0);
  EXPECT_GT(wrong_normals(1e-6, beside, checked), 0);
}

TEST(DockingScene, TheFrictionVariantCarriesTheFrankaValues) {
  DockingSceneOptions options;
  options.joint_friction = true;
  const DockingScene scene = build_docking_scene(options);
  const mjModel& m = scene.robot.model();
  for (int j = 0; j < 7; ++j) {
    EXPECT_DOUBLE_EQ(m.dof_frictionloss[scene.chain.dof_address(j)], kFrankaFrictionLoss[j]);
    EXPECT_GT(m.dof_damping[scene.chain.dof_address(j)], 0.0);
  }
}

TEST(DockingScene, WithoutTheSensorTheSiteHasNone) {
  DockingSceneOptions options;
  options.ft_sensor = false;
  const DockingScene scene = build_docking_scene(options);
  EXPECT_EQ(scene.robot.model().nsensor, 0);
  const std::string message =
      error_of([&] { ForceTorqueSensor(scene.robot, DockingNames::ft_site); });
  EXPECT_TRUE(contains(message, "iiwa/peg/ft")) << message;
  EXPECT_TRUE(contains(message, "no force sensor")) << message;
}

TEST(DockingScene, BadGeometryIsNamed) {
  auto message = [](auto edit) {
    DockingSceneOptions options;
    edit(options);
    return error_of([&] { docking_scene(options); });
  };
  EXPECT_TRUE(contains(message([](auto& o) { o.geometry.bore_radius = 0.014; }),
                       "must be wider than the peg"));
  EXPECT_TRUE(
      contains(message([](auto& o) { o.geometry.sides = 6; }), "sides must be in [8, 256], got 6"));
  EXPECT_TRUE(contains(message([](auto& o) { o.geometry.peg_length = 0.04; }),
                       "longer than the hole is deep"));
  EXPECT_TRUE(contains(message([](auto& o) { o.geometry.chamfer = std::nan(""); }), "chamfer"));
  EXPECT_TRUE(contains(message([](auto& o) { o.geometry.solimp = {0.99, 0.9, 0.001}; }), "solimp"));
  EXPECT_TRUE(contains(message([](auto& o) { o.geometry.ccd_tolerance = 0.0; }), "ccd_tolerance"));
  EXPECT_TRUE(contains(message([](auto& o) { o.X_WS.p.z() = 0.03; }), "below the floor"));
  EXPECT_TRUE(contains(message([](auto& o) {
                         o.X_WS.R =
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).toRotationMatrix();
                       }),
                       "straight up"));
}

}  // namespace
}  // namespace mjarm
