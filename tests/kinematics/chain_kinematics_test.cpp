#include "mjarm/kinematics/chain_kinematics.hpp"

#include <gtest/gtest.h>

#include <random>

#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "support/test_models.hpp"

namespace mjarm {
namespace {

Eigen::VectorXd random_q(const Chain& chain, std::mt19937& rng) {
  Eigen::VectorXd q(chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    const double lo = std::isfinite(chain.lower()[i]) ? chain.lower()[i] : -3.0;
    const double hi = std::isfinite(chain.upper()[i]) ? chain.upper()[i] : 3.0;
    q[i] = std::uniform_real_distribution<double>(lo, hi)(rng);
  }
  return q;
}

/// Pose and world-aligned Jacobian of a chain's frame computed by MuJoCo itself.
struct MujocoReference {
  Pose X_WE;
  Matrix6Xd J;
};

MujocoReference mujoco_reference(const Chain& chain, mjData* d, const Eigen::VectorXd& q) {
  const mjModel& m = chain.robot().model();
  chain.scatter(q, d->qpos);
  mj_kinematics(&m, d);
  mj_comPos(&m, d);
  MujocoReference ref;
  std::vector<double> jacp(3 * m.nv), jacr(3 * m.nv);
  const FrameRef& f = chain.frame();
  const double* pos = f.kind == FrameKind::site ? d->site_xpos + 3 * f.id : d->xpos + 3 * f.id;
  const double* mat = f.kind == FrameKind::site ? d->site_xmat + 9 * f.id : d->xmat + 9 * f.id;
  ref.X_WE.p = Eigen::Map<const Eigen::Vector3d>(pos);
  ref.X_WE.R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
  if (f.kind == FrameKind::site) {
    mj_jacSite(&m, d, jacp.data(), jacr.data(), f.id);
  } else {
    mj_jacBody(&m, d, jacp.data(), jacr.data(), f.id);
  }
  ref.J.resize(6, chain.size());
  for (int i = 0; i < chain.size(); ++i) {
    const int dof = chain.dof_address(i);
    for (int r = 0; r < 3; ++r) {
      ref.J(r, i) = jacp[r * m.nv + dof];
      ref.J(3 + r, i) = jacr[r * m.nv + dof];
    }
  }
  return ref;
}

/// FK and the world-aligned Jacobian against MuJoCo's at @p trials random q, to 1e-12.
void expect_matches_mujoco(const Chain& chain, std::mt19937& rng, int trials) {
  ChainKinematics kin(chain);
  DataPtr d = chain.robot().make_data();
  Matrix6Xd J(6, chain.size());
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd q = random_q(chain, rng);
    const MujocoReference ref = mujoco_reference(chain, d.get(), q);
    kin.update(q);
    kin.jacobian(J);
    EXPECT_LT((kin.pose().p - ref.X_WE.p).norm(), 1e-12);
    EXPECT_LT((kin.pose().R - ref.X_WE.R).norm(), 1e-12);
    EXPECT_LT((J - ref.J).norm(), 1e-12);
  }
}

class ChainKinematicsTest : public ::testing::Test {
 protected:
  Robot robot_ = Robot::from_string(test::kTrickyArm);
};

TEST_F(ChainKinematicsTest, MatchesMujocoOnTrickyArm) {
  const Chain chain(robot_, "tool");
  ASSERT_EQ(chain.size(), 5);  // the off-path hinge and the free box are not on the path
  std::mt19937 rng(7);
  expect_matches_mujoco(chain, rng, 200);
}

TEST(ChainKinematicsAxes, CoordinateAxisJointsMatchMujoco) {
  // the two-column rotation of a joint about ±e_k (at the body origin or not) and the general
  // Rodrigues product, against MuJoCo: negative axes, every k, and the bundled arms
  const Robot signed_axes = Robot::from_string(R"(
<mujoco>
  <default><geom size="0.02" mass="0.1"/></default>
  <worldbody>
    <body name="a" pos="0.1 0 0.2" euler="0.2 0.1 -0.3">
      <geom/>
      <joint name="n1" axis="0 0 -1" range="-3 3"/>
      <body name="b" pos="0 0.1 0.3">
          <geom/>
        <joint name="n2" axis="0 -1 0" pos="0.02 0 0.01" range="-3 3"/>
        <body name="c" pos="0.2 0 0" euler="0.4 0 0.2">
          <geom/>
          <joint name="n3" axis="-1 0 0" range="-3 3"/>
          <body name="d" pos="0 0 0.1">
          <geom/>
            <joint name="n4" axis="1 0 0" pos="0 0.03 0" range="-3 3"/>
            <joint name="n5" axis="0 0.6 0.8" range="-3 3"/>
            <site name="tip" pos="0.01 0.02 0.1"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>)");
  std::vector<Chain> chains{Chain(signed_axes, "tip")};
  for (const char* arm : {"panda", "ur5e", "iiwa14", "arm6"})
    chains.emplace_back(Robot::bundled(arm),
                        arm == std::string("arm6") ? "grip" : "attachment_site");
  std::mt19937 rng(29);
  for (const Chain& chain : chains) {
    SCOPED_TRACE(chain.robot().name());
    expect_matches_mujoco(chain, rng, 30);
  }
}

TEST_F(ChainKinematicsTest, BodyFrameAndExplicitJointList) {
  // j2 and j4 only; the others stay at the fixed configuration we set
  const Chain chain(robot_, {"j4", "j2", "off_path"}, "l3");
  ChainKinematics kin(chain);
  DataPtr d = robot_.make_data();
  std::mt19937 rng(3);
  Eigen::VectorXd fixed = Eigen::Map<const Eigen::VectorXd>(robot_.model().qpos0, robot_.nq());
  fixed[robot_.model().jnt_qposadr[robot_.joint("j1")]] = 0.7;
  fixed[robot_.model().jnt_qposadr[robot_.joint("j3")]] = 0.05;
  kin.set_fixed_qpos(fixed);
  Matrix6Xd J(6, 3);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q = random_q(chain, rng);
    Eigen::Map<Eigen::VectorXd>(d->qpos, robot_.nq()) = fixed;
    const MujocoReference ref = mujoco_reference(chain, d.get(), q);
    kin.update(q);
    kin.jacobian(J);
    EXPECT_LT((kin.pose().p - ref.X_WE.p).norm(), 1e-12);
    EXPECT_LT((kin.pose().R - ref.X_WE.R).norm(), 1e-12);
    EXPECT_LT((J - ref.J).norm(), 1e-12);
    EXPECT_EQ(J.col(2).norm(), 0.0);  // off_path does not move l3
  }
  EXPECT_FALSE(kin.moves_frame(2));
}

TEST_F(ChainKinematicsTest, JacobianFramesAgreeWithFiniteDifferences) {
  const Chain chain(robot_, "tool");
  ChainKinematics kin(chain);
  std::mt19937 rng(11);
  const int n = chain.size();
  Matrix6Xd J_aligned(6, n), J_local(6, n), J_world(6, n), fd(6, n);
  FiniteDifferenceWorkspace workspace(n, 6);
  const auto fk = [&kin](const Eigen::VectorXd& x) -> const Pose& { return kin.update(x); };
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_q(chain, rng);
    // [ṗ; ω] per joint, from central differences of the pose (world-aligned)
    finite_difference_pose_jacobian(fk, q, fd, workspace);
    const Pose X = kin.update(q);
    kin.jacobian(J_aligned, JacobianFrame::world_aligned);
    kin.jacobian(J_local, JacobianFrame::local);
    kin.jacobian(J_world, JacobianFrame::world);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d v = fd.col(i).head<3>();
      const Eigen::Vector3d w = fd.col(i).tail<3>();
      EXPECT_LT((J_aligned.col(i).head<3>() - v).norm(), 1e-8);
      EXPECT_LT((J_aligned.col(i).tail<3>() - w).norm(), 1e-8);
      EXPECT_LT((J_local.col(i).head<3>() - X.R.transpose() * v).norm(), 1e-8);
      EXPECT_LT((J_local.col(i).tail<3>() - X.R.transpose() * w).norm(), 1e-8);
      EXPECT_LT((J_world.col(i).head<3>() - (v - w.cross(X.p))).norm(), 1e-8);
    }
  }
}

TEST_F(ChainKinematicsTest, BiasAccelerationMatchesFiniteDifferenceOfJacobian) {
  const Chain chain(robot_, "tool");
  ChainKinematics kin(chain);
  std::mt19937 rng(5);
  const int n = chain.size();
  Matrix6Xd J(6, n);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_q(chain, rng);
    Eigen::VectorXd qd = Eigen::VectorXd::Random(n);
    // dJ/dt along q(t) = q + t·q̇
    const auto jacobian_at = [&](double t) {
      kin.update(q + t * qd);
      kin.jacobian(J);
      return J;
    };
    const Vector6d expected = finite_difference_derivative(jacobian_at, 0.0) * qd;
    kin.update(q);
    EXPECT_LT((kin.bias_acceleration(qd) - expected).norm(), 1e-7);
  }
}

// the same J̇·q̇ from MuJoCo's own mj_jacDot at the frame point (two methods cross-checked)
TEST_F(ChainKinematicsTest, BiasAccelerationMatchesMujocosJacobianDerivative) {
  const Chain chain(robot_, "tool");
  ChainKinematics kin(chain);
  const mjModel& m = robot_.model();
  DataPtr d = robot_.make_data();
  const int site = robot_.site("tool");
  const int n = chain.size();
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> jacp(3, m.nv), jacr(3, m.nv);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_q(chain, rng);
    const Eigen::VectorXd qd = Eigen::VectorXd::Random(n);
    mj_resetData(&m, d.get());
    chain.scatter(q, d->qpos);
    for (int i = 0; i < n; ++i) d->qvel[chain.dof_address(i)] = qd[i];  // other dofs at rest
    mj_forward(&m, d.get());
    mj_jacDot(&m, d.get(), jacp.data(), jacr.data(), d->site_xpos + 3 * site,
              m.site_bodyid[site]);
    const Eigen::Map<const Eigen::VectorXd> qvel(d->qvel, m.nv);
    Vector6d expected;
    expected << jacp * qvel, jacr * qvel;
    kin.update(q);
    EXPECT_LT((kin.bias_acceleration(qd) - expected).norm(), 1e-10) << trial;
  }
}

TEST_F(ChainKinematicsTest, CostDoesNotDependOnOtherBodies) {
  // the chain walks only its own path: the free box and the branch are never visited
  const Chain chain(robot_, "tool");
  ChainKinematics kin(chain);
  Eigen::VectorXd fixed = Eigen::Map<const Eigen::VectorXd>(robot_.model().qpos0, robot_.nq());
  fixed[robot_.model().jnt_qposadr[robot_.joint("box_free")]] = 1e9;  // far away, irrelevant
  const Pose before = kin.update(chain.center());
  kin.set_fixed_qpos(fixed);
  const Pose after = kin.update(chain.center());
  EXPECT_EQ((before.p - after.p).norm(), 0.0);
}

TEST_F(ChainKinematicsTest, BadFixedQposIsRejected) {
  ChainKinematics kin(Chain(robot_, "tool"));
  EXPECT_THROW(kin.set_fixed_qpos(Eigen::VectorXd::Zero(3)), Error);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(robot_.nq());
  bad[0] = std::nan("");
  EXPECT_THROW(kin.set_fixed_qpos(bad), Error);
}

}  // namespace
}  // namespace mjarm
