// WeldGrasp: the eq_data layout as the engine reads it, the jump when a weld is switched on
// (measured), release, solref, and the model copy that keeps simulations apart.

#include "mjarm/sim/weld_grasp.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/scene/free_pose.hpp"
#include "mjarm/scene/scene.hpp"
#include "mjarm/sim/simulation.hpp"
#include "sim/sim_test_support.hpp"
#include "support/error_message.hpp"

namespace mjarm {
namespace {

// arm6 at home with a cube held between its open fingers, 1 mm above the table, and a weld
// between the flange body and the cube (inactive, as Scene::add_weld declares it)
struct WeldScene {
  Robot robot;
  std::vector<double> qpos;  // home, with the cube under the grip site
};

WeldScene weld_scene() {
  Scene scene("weld_test");
  scene.add_arena();
  scene.add_robot({"arm6", "arm6", {0, 0, 0}, {1, 0, 0, 0}, false});
  ObjectSpec cube;
  cube.name = "cube";
  cube.size = {0.015, 0.015, 0.015};
  cube.mass = 0.05;
  cube.pos = {0.6, 0.3, 0.9};  // far from where the grasp happens: the compiled relpose is wrong
  scene.add_object(cube);
  scene.add_weld({"grasp", "arm6/link6", "cube", false, {0.002, 1.0}});
  WeldScene out{scene.compile(), {}};
  const mjModel& m = out.robot.model();
  out.qpos = out.robot.keyframe_qpos("home");
  // the cube under the grip site, turned 20° about z, resting 1 mm above the table top
  DataPtr d = out.robot.make_data();
  std::copy(out.qpos.begin(), out.qpos.end(), d->qpos);
  mj_forward(&m, d.get());
  const double* grip = d->site_xpos + 3 * out.robot.site("arm6/grip");
  const double half = std::sin(0.5 * 20.0 * M_PI / 180.0);
  set_free_pose(out.robot, *d, "cube",
                {{grip[0], grip[1], 0.75 + 0.015 + 0.001},
                 {std::cos(0.5 * 20.0 * M_PI / 180.0), 0, 0, half}});
  out.qpos.assign(d->qpos, d->qpos + m.nq);
  return out;
}

// largest |residual| of the weld's constraint rows in the current state
double weld_residual(const Simulation& sim, int weld) {
  const mjData& d = sim.data();
  double worst = 0.0;
  for (int r = 0; r < d.nefc; ++r) {
    if (d.efc_type[r] == mjCNSTR_EQUALITY && d.efc_id[r] == weld)
      worst = std::max(worst, std::abs(d.efc_pos[r]));
  }
  return worst;
}

Eigen::Vector3d body_position(const Simulation& sim, int body) {
  return Eigen::Map<const Eigen::Vector3d>(sim.data().xpos + 3 * body);
}

SimulationOptions position_mode() {
  SimulationOptions o;
  o.mode = SimulationMode::position;
  return o;
}

// the arm and fingers held by their servos at the state's positions (gravity compensated by the
// simulation): a robot standing still, as a grasp is made
struct Holder {
  Chain chain;
  test::PositionTarget controller;
  Reference reference;
  explicit Holder(Simulation& sim)
      : chain(sim.robot(),
              {"arm6/joint1", "arm6/joint2", "arm6/joint3", "arm6/joint4", "arm6/joint5",
               "arm6/joint6", "arm6/finger_left", "arm6/finger_right"},
              "arm6/grip"),
        controller(chain) {
    sim.add_controller(controller);
    reference.joint.q = chain.gather(sim.data().qpos);
  }
};

// ticks until `until` [s]; returns the largest distance the body moved from where it was at the
// start
double hold(Simulation& sim, const Holder& holder, int body, double until) {
  const Eigen::Vector3d start = body_position(sim, body);
  double moved = 0.0;
  while (sim.time() < until - 1e-9) {
    EXPECT_TRUE(sim.tick(holder.reference).ok());
    moved = std::max(moved, (body_position(sim, body) - start).norm());
  }
  return moved;
}

TEST(WeldGrasp, EqDataLayoutIsTheOneTheEngineReads) {
  // a weld written by activate() is satisfied exactly in the state it was read from: every
  // constraint row of the weld (3 position, 3 orientation) has a zero residual, so the layout
  // is [anchor in body2 (3), anchor in body1 (3), q_12 (4), torque scale]
  const WeldScene s = weld_scene();
  Simulation sim(s.robot, position_mode());
  EXPECT_FALSE(sim.owns_model());  // switching equalities needs no copy: eq_active is state
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  WeldGrasp grasp(sim, "grasp");
  ASSERT_TRUE(sim.owns_model());  // the grasp's relative pose is model data: a copy of its own
  ASSERT_TRUE(grasp.activate());
  sim.forward();
  int rows = 0;
  for (int r = 0; r < sim.data().nefc; ++r)
    rows += sim.data().efc_type[r] == mjCNSTR_EQUALITY && sim.data().efc_id[r] == grasp.equality();
  EXPECT_EQ(rows, 6);
  EXPECT_LT(weld_residual(sim, grasp.equality()), 1e-12);

  // the compiler's data is the relative pose at qpos0 (the cube where the file put it): there
  // the weld holds, here it is off by the cube's displacement since
  const mjModel& file = s.robot.model();
  const double* compiled = file.eq_data + mjNEQDATA * grasp.equality();
  std::vector<double> as_compiled(compiled, compiled + mjNEQDATA);
  ASSERT_TRUE(sim.set_equality_data(grasp.equality(), as_compiled));
  sim.forward();
  EXPECT_GT(weld_residual(sim, grasp.equality()), 0.1);
  std::vector<double> qpos0(file.qpos0, file.qpos0 + file.nq);
  sim.set_state(qpos0, std::vector<double>(s.robot.nv(), 0.0));
  EXPECT_LT(weld_residual(sim, grasp.equality()), 1e-9);

  // the layout written: anchor 0, p_12 = R_1ᵀ(p_2 − p_1), q_12 = q_1⁻¹q_2, torque scale kept
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  ASSERT_TRUE(grasp.activate());
  const std::span<const double> data = sim.equality_data(grasp.equality());
  const Pose& X_12 = grasp.relative_pose();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(data[i], 0.0);
    EXPECT_NEAR(data[3 + i], X_12.p[i], 1e-15);
  }
  const Eigen::Quaterniond q12(X_12.R);
  EXPECT_NEAR(
      std::abs(data[6] * q12.w() + data[7] * q12.x() + data[8] * q12.y() + data[9] * q12.z()), 1.0,
      1e-12);
  EXPECT_EQ(data[10], compiled[10]);
}

TEST(WeldGrasp, SwitchingOnMovesTheObjectLessThanFiftyMicrometres) {
  const WeldScene s = weld_scene();
  const int cube = s.robot.body("cube");
  // done right: the relative pose of the current state
  Simulation sim(s.robot, position_mode());
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  const Holder holder(sim);
  hold(sim, holder, cube, 0.5);  // the cube settles on the table
  WeldGrasp grasp(sim, "grasp");
  ASSERT_TRUE(grasp.activate());
  const double jump = hold(sim, holder, cube, sim.time() + 0.5);
  EXPECT_LT(jump, 0.05e-3);
  EXPECT_LT(grasp.deviation(), 0.05e-3);
  RecordProperty("weld_jump_mm", std::to_string(jump * 1e3));

  // switched on as compiled (eq_active only): the cube is yanked towards where the file had it
  Simulation naive(s.robot, position_mode());
  naive.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  const Holder naive_holder(naive);
  hold(naive, naive_holder, cube, 0.5);
  ASSERT_TRUE(naive.set_equality_active(naive.equality("grasp"), true));
  EXPECT_GT(hold(naive, naive_holder, cube, naive.time() + 0.5), 0.01);
}

// MuJoCo 4's mj_setConst recomputes the pose of a weld compiled without relpose (eq_data[11]
// set) at qpos0; a pose activate wrote must survive it (domain randomization calls it)
TEST(WeldGrasp, TheActivatedPoseSurvivesSetConst) {
  const WeldScene s = weld_scene();
  Simulation sim(s.robot, position_mode());
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  WeldGrasp grasp(sim, "grasp");
  const int weld = sim.equality("grasp");
  ASSERT_NE(sim.model().eq_data[weld * mjNEQDATA + 11], 0.0);  // as compiled: MuJoCo's mark
  ASSERT_TRUE(grasp.activate());
  const std::vector<double> written(sim.model().eq_data + weld * mjNEQDATA,
                                    sim.model().eq_data + (weld + 1) * mjNEQDATA);
  DataPtr scratch = s.robot.make_data();
  mj_setConst(sim.editable_model(), scratch.get());
  for (int i = 0; i < mjNEQDATA; ++i)
    EXPECT_EQ(sim.model().eq_data[weld * mjNEQDATA + i], written[i]) << "eq_data[" << i << "]";
}

TEST(WeldGrasp, HoldsWhileTheArmMovesAndReleaseRestoresFreeMotion) {
  const WeldScene s = weld_scene();
  const int cube = s.robot.body("cube");
  Simulation sim(s.robot, position_mode());
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  Holder holder(sim);
  hold(sim, holder, cube, 0.3);
  WeldGrasp grasp(sim, "grasp");
  ASSERT_TRUE(grasp.activate());
  EXPECT_TRUE(grasp.active());
  // lift: shoulder pitch back by 0.3 rad over 0.5 s; the cube follows the flange
  const double z0 = body_position(sim, cube).z();
  const double q1 = holder.reference.joint.q[1];
  while (sim.time() < 0.8) {
    holder.reference.joint.q[1] = q1 - 0.3 * std::min(1.0, (sim.time() - 0.3) / 0.5);
    ASSERT_TRUE(sim.tick(holder.reference).ok());
  }
  hold(sim, holder, cube, 1.2);
  const double lifted = body_position(sim, cube).z();
  EXPECT_GT(lifted - z0, 0.02);
  EXPECT_LT(grasp.deviation(), 0.2e-3);  // the 50 g cube sags by less than that on the weld

  // released: the cube falls freely, h = g·t²/2 after 0.1 s (4.9 cm; open fingers never touch it)
  grasp.release();
  EXPECT_FALSE(grasp.active());
  const double t0 = sim.time();
  hold(sim, holder, cube, t0 + 0.1);
  const double fallen = lifted - body_position(sim, cube).z();
  const double g = -s.robot.model().opt.gravity[2];
  EXPECT_NEAR(fallen, 0.5 * g * (sim.time() - t0) * (sim.time() - t0), 2e-3);
}

TEST(WeldGrasp, SolrefIsTheOneAsked) {
  const WeldScene s = weld_scene();
  Simulation sim(s.robot, position_mode());
  const WeldGrasp grasp(sim, "grasp", {0.02, 0.7});
  EXPECT_DOUBLE_EQ(sim.model().eq_solref[mjNREF * grasp.equality()], 0.02);
  EXPECT_DOUBLE_EQ(sim.model().eq_solref[mjNREF * grasp.equality() + 1], 0.7);
  EXPECT_DOUBLE_EQ(s.robot.model().eq_solref[mjNREF * grasp.equality()], 0.002);  // the file's
  // a softer weld lets the same load pull the cube further from its grasped pose
  const auto sag = [&](double time_constant) {
    Simulation run(s.robot, position_mode());
    run.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
    Holder holder(run);
    WeldGrasp weld(run, "grasp", {time_constant, 1.0});
    const int cube = s.robot.body("cube");
    Eigen::Vector3d p = body_position(run, cube);
    p.z() += 0.02;  // lifted off the table, hanging on the weld
    set_free_pose(s.robot, run.data(), "cube",
                  {{p.x(), p.y(), p.z()}, free_pose(s.robot, run.data(), "cube").quat_WB});
    run.forward();
    EXPECT_TRUE(weld.activate());
    hold(run, holder, cube, 0.5);
    return weld.deviation();
  };
  EXPECT_LT(sag(0.002), sag(0.05));
}

TEST(WeldGrasp, TwoSimulationsOfOneRobotNeverSeeEachOthersGrasps) {
  const WeldScene s = weld_scene();
  const int cube = s.robot.body("cube");
  Simulation a(s.robot, position_mode());
  Simulation b(s.robot, position_mode());
  for (Simulation* sim : {&a, &b}) {
    std::vector<double> q = s.qpos;
    q[static_cast<std::size_t>(free_qpos_address(s.robot, "cube")) + 2] += 0.05;  // in the air
    sim->set_state(q, std::vector<double>(s.robot.nv(), 0.0));
  }
  Holder ha(a), hb(b);
  WeldGrasp grasp(a, "grasp");
  // the grasp's model data lives in a's own copy; b still steps the robot's model
  ASSERT_NE(&a.model(), &s.robot.model());
  ASSERT_EQ(&b.model(), &s.robot.model());
  ASSERT_TRUE(grasp.activate());
  EXPECT_TRUE(a.equality_active(grasp.equality()));
  EXPECT_FALSE(b.equality_active(grasp.equality()));
  EXPECT_EQ(s.robot.model().eq_active0[grasp.equality()], 0);
  const double za = body_position(a, cube).z(), zb = body_position(b, cube).z();
  hold(a, ha, cube, 0.15);
  hold(b, hb, cube, 0.15);
  EXPECT_NEAR(body_position(a, cube).z(), za, 0.2e-3);  // held
  EXPECT_LT(body_position(b, cube).z(), zb - 0.04);     // fell onto the table
  // the second simulation's own grasp is its own too
  WeldGrasp other(b, "grasp");
  ASSERT_TRUE(other.activate());
  grasp.release();
  EXPECT_FALSE(a.equality_active(grasp.equality()));
  EXPECT_TRUE(b.equality_active(other.equality()));
}

// One model-ownership mechanism: a simulation owns one copy, whether its owner asked for it
// (own_model, for randomization) or a weld grasp did; the grasp's data and the owner's edits land
// in that same copy, the switches in the data, and the robot's model keeps the file's values.
TEST(WeldGrasp, OneModelCopyServesTheGraspsAndTheOwnersEdits) {
  const WeldScene s = weld_scene();
  SimulationOptions options = position_mode();
  options.own_model = true;
  Simulation sim(s.robot, options);
  ASSERT_TRUE(sim.owns_model());
  ASSERT_EQ(sim.editable_model(), &sim.model());
  const int cube = s.robot.body("cube");
  const double mass = s.robot.model().body_mass[cube];
  sim.editable_model()->body_mass[cube] = 2.0 * mass;
  WeldGrasp grasp(sim, "grasp");
  ASSERT_TRUE(grasp.activate());
  EXPECT_TRUE(sim.equality_active(grasp.equality()));
  EXPECT_EQ(sim.model().body_mass[cube], 2.0 * mass);
  EXPECT_EQ(s.robot.model().body_mass[cube], mass);
  EXPECT_EQ(s.robot.model().eq_active0[grasp.equality()], 0);
  // without own_model and without a grasp the robot's model is shared, and its switches too
  // are the simulation's own (state)
  Simulation plain(s.robot, position_mode());
  EXPECT_FALSE(plain.owns_model());
  EXPECT_EQ(plain.editable_model(), nullptr);
  EXPECT_TRUE(plain.set_equality_active(grasp.equality(), true));
  EXPECT_TRUE(plain.equality_active(grasp.equality()));
  EXPECT_EQ(s.robot.model().eq_active0[grasp.equality()], 0);
  // a reset restores the model's initial switch
  plain.reset();
  EXPECT_FALSE(plain.equality_active(grasp.equality()));
  // the grasp's model data needs the copy, which the grasp asks for
  EXPECT_NE(test::error_of([&] { plain.set_equality_solref(grasp.equality(), 0.01, 1.0); })
                .find("own_model"),
            std::string::npos);
  WeldGrasp second(plain, "grasp");
  EXPECT_TRUE(plain.owns_model());
  EXPECT_EQ(plain.model().body_mass[cube], mass);
}

TEST(WeldGrasp, ActivateAndReleaseAllocateNothing) {
  const WeldScene s = weld_scene();
  Simulation sim(s.robot, position_mode());
  sim.set_state(s.qpos, std::vector<double>(s.robot.nv(), 0.0));
  WeldGrasp grasp(sim, "grasp");
  const std::uint64_t before = test::malloc_calls();
  for (int i = 0; i < 10; ++i) {
    EXPECT_TRUE(grasp.activate());
    (void)grasp.deviation();
    grasp.release();
  }
  EXPECT_EQ(test::malloc_calls() - before, 0u);
}

TEST(WeldGrasp, BadInput) {
  const WeldScene s = weld_scene();
  Simulation sim(s.robot, position_mode());
  EXPECT_NE(test::error_of([&] { WeldGrasp(sim, "grap"); }).find("closest: grasp"),
            std::string::npos);
  // welds on bodies that do not exist
  const std::string missing = test::error_of([&] { WeldGrasp::between(sim, "arm6/link6", "cub"); });
  EXPECT_NE(missing.find("'cub'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("cube"), std::string::npos) << missing;
  const std::string none = test::error_of([&] { WeldGrasp::between(sim, "arm6/link5", "cube"); });
  EXPECT_NE(none.find("no weld between body 'arm6/link5' and body 'cube'"), std::string::npos)
      << none;
  EXPECT_EQ(WeldGrasp::between(sim, "cube", "arm6/link6").equality(), sim.equality("grasp"));
  EXPECT_NE(test::error_of([&] {
              WeldGrasp(sim, "grasp", {0.0, 1.0});
            }).find("positive"),
            std::string::npos);
  EXPECT_NE(test::error_of([&] {
              WeldGrasp(sim, "grasp", {0.002, NAN});
            }).find("positive"),
            std::string::npos);
  // an equality that is not a weld
  const Robot joint_coupled = Robot::from_string(R"(<mujoco><worldbody>
      <body><joint name="a" type="slide"/><geom size="0.1"/></body>
      <body><joint name="b" type="slide"/><geom size="0.1"/></body></worldbody>
      <equality><joint name="couple" joint1="a" joint2="b"/></equality></mujoco>)");
  Simulation coupled(joint_coupled);
  EXPECT_NE(test::error_of([&] { WeldGrasp(coupled, "couple"); }).find("is not a weld"),
            std::string::npos);
  // a model without equality constraints shares its model and refuses to switch any
  const Robot plain = Robot::bundled("arm6");
  Simulation shared(plain);
  EXPECT_FALSE(shared.owns_model());
  EXPECT_FALSE(shared.set_equality_active(0, true));
  EXPECT_NE(test::error_of([&] { (void)shared.equality("grasp"); }).find("grasp"),
            std::string::npos);
}

}  // namespace
}  // namespace mjarm
