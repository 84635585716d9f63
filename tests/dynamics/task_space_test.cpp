#include "mjarm/dynamics/task_space.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "dynamics/dynamics_test_support.hpp"
#include "ik/malloc_counter.hpp"
#include "mjarm/error.hpp"
#include "support/reference_linear_algebra.hpp"

namespace mjarm {
namespace {

using test::random_state;

double rel(double scale) { return 1e-9 * (1.0 + scale); }

TEST(TaskSpaceDynamics, IdentitiesAwayFromSingularities) {
  std::mt19937 rng(5);
  int checked = 0;
  for (const auto& arm : test::dynamics_arms()) {
    const Chain chain(Robot::bundled(arm.robot), arm.frame);
    SCOPED_TRACE(arm.robot);
    // planar2 moves in a plane: only its position rows x, z make a full-rank task
    const bool planar = chain.size() < 6;
    DataPtr d = chain.robot().make_data();
    ChainDynamics dyn(chain);
    TaskSpaceDynamics ts(chain.size(), planar ? 2 : 6);
    Eigen::MatrixXd J(ts.task_rows(), chain.size());
    for (int trial = 0; trial < 20; ++trial) {
      random_state(chain, d.get(), rng);
      dyn.update(*d);
      if (planar) {
        J << dyn.jacobian().row(0), dyn.jacobian().row(2);
      } else {
        J = dyn.jacobian();
      }
      if (ts.update(dyn.mass_matrix(), J) != TaskSpaceStatus::ok)
        continue;  // too close to singular
      ++checked;
      const int n = chain.size();
      const int m = ts.task_rows();
      const Eigen::MatrixXd Minv = test::inverse(dyn.mass_matrix());
      const Eigen::MatrixXd A = J * Minv * J.transpose();
      const Eigen::MatrixXd I_m = Eigen::MatrixXd::Identity(m, m);
      const Eigen::MatrixXd& L = ts.lambda();
      const Eigen::MatrixXd& Jbar = ts.jbar();
      const Eigen::MatrixXd& N = ts.nullspace();
      EXPECT_LT((ts.mass_inverse() - Minv).norm(), rel(Minv.norm()));
      EXPECT_LT((L * A - I_m).norm(), 1e-8 * ts.condition());
      EXPECT_LT((L - test::inverse(A)).norm(), 1e-8 * ts.condition() * (1.0 + L.norm()));
      EXPECT_LT((J * Jbar - I_m).norm(), 1e-8 * ts.condition());
      EXPECT_LT((N * Jbar).norm(), 1e-8 * ts.condition() * (1.0 + Jbar.norm()));
      EXPECT_LT((J * N).norm(), 1e-8 * ts.condition() * (1.0 + J.norm()));
      EXPECT_LT((N * N - N).norm(), 1e-8 * ts.condition() * (1.0 + N.norm()));
      // M-weighted symmetry: N·M⁻¹ = M⁻¹·Nᵀ, and Nᵀ torques make no task acceleration
      EXPECT_LT((N * Minv - Minv * N.transpose()).norm(), 1e-9 * (1.0 + Minv.norm()));
      const Eigen::MatrixXd& M = dyn.mass_matrix();
      EXPECT_LT((M * N - N.transpose() * M).norm(), 1e-8 * ts.condition() * (1.0 + M.norm()));
      const Eigen::VectorXd tau0 = Eigen::VectorXd::Random(n);
      Eigen::VectorXd tau(n);
      ts.project_torque(tau0, tau);
      EXPECT_LT((tau - N.transpose() * tau0).norm(), rel(tau.norm()));
      EXPECT_LT((J * Minv * tau).norm(), 1e-8 * ts.condition() * (1.0 + tau0.norm()));
      EXPECT_GT(ts.min_singular_value(), 0.0);
      EXPECT_NEAR(ts.min_singular_value() * ts.min_singular_value(), ts.eigenvalues()[0], 1e-15);
    }
  }
  EXPECT_GT(checked, 60);  // most random states are regular
}

TEST(TaskSpaceDynamics, BoundedThroughTheElbowSingularity) {
  // planar2 stretched out (elbow = 0) cannot move its tip along the arm: J·M⁻¹·Jᵀ is singular
  const Chain chain(Robot::bundled("planar2"), "tip");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  TaskSpaceDynamics ts(2, 2);
  const double floor = ts.options().min_eigenvalue;
  Eigen::MatrixXd J(2, 2);
  double previous_sigma = INFINITY;
  bool saw_ok = false;
  bool saw_damped = false;
  for (double elbow = -0.6; elbow <= 1e-12; elbow += 0.01) {
    Eigen::Vector2d q(0.3, elbow);
    chain.scatter(q, d->qpos);
    mju_zero(d->qvel, chain.robot().model().nv);
    mj_forward(&chain.robot().model(), d.get());
    dyn.update(*d);
    J << dyn.jacobian().row(0), dyn.jacobian().row(2);
    const TaskSpaceStatus status = ts.update(dyn.mass_matrix(), J);
    (status == TaskSpaceStatus::ok ? saw_ok : saw_damped) = true;
    EXPECT_TRUE(ts.lambda().allFinite());
    EXPECT_TRUE(ts.jbar().allFinite());
    EXPECT_TRUE(ts.nullspace().allFinite());
    // no direction of Λ exceeds 1/floor, and Λ stays symmetric positive definite
    const Eigen::VectorXd lambda_eigenvalues = test::symmetric_eigenvalues(ts.lambda());
    EXPECT_LE(lambda_eigenvalues.maxCoeff(), (1.0 + 1e-9) / floor);
    EXPECT_GT(lambda_eigenvalues.minCoeff(), 0.0);
    EXPECT_EQ(status == TaskSpaceStatus::damped, ts.eigenvalues()[0] < floor);
    // the M-weighted symmetry survives the damping
    const Eigen::MatrixXd& Minv = ts.mass_inverse();
    EXPECT_LT((ts.nullspace() * Minv - Minv * ts.nullspace().transpose()).norm(), 1e-9);
    const Eigen::MatrixXd& M = dyn.mass_matrix();
    EXPECT_LT((M * ts.nullspace() - ts.nullspace().transpose() * M).norm(), 1e-9);
    EXPECT_LE(ts.min_singular_value(), previous_sigma + 1e-12);  // shrinks towards the singularity
    previous_sigma = ts.min_singular_value();
  }
  EXPECT_TRUE(saw_ok);
  EXPECT_TRUE(saw_damped);
  EXPECT_LT(previous_sigma, 1e-6);
  EXPECT_GT(ts.condition(), 1e9);
}

// Λ, J̄, N, M⁻¹ and the eigenvalues of two instances, one forced onto the eigen path.
void expect_same_outputs(const TaskSpaceDynamics& a, const TaskSpaceDynamics& b) {
  const auto close = [](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    return (x - y).norm() <= 1e-9 * (1.0 + y.norm());
  };
  EXPECT_EQ(a.status(), b.status());
  EXPECT_TRUE(close(a.lambda(), b.lambda()));
  EXPECT_TRUE(close(a.lambda_inverse(), b.lambda_inverse()));
  EXPECT_TRUE(close(a.jbar(), b.jbar()));
  EXPECT_TRUE(close(a.nullspace(), b.nullspace()));
  EXPECT_TRUE(close(a.mass_inverse(), b.mass_inverse()));
  EXPECT_TRUE(close(a.eigenvalues(), b.eigenvalues()));
}

TEST(TaskSpaceDynamics, CholeskyFastPathMatchesEigenPath) {
  // random panda states: the fast path certifies most of them, and then agrees with the
  // eigendecomposition; the eigen path is taken exactly when an eigenvalue is at the floor
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  TaskSpaceOptions forced;
  forced.always_eigendecompose = true;
  std::mt19937 rng(11);
  for (const int rows : {6, 3}) {
    TaskSpaceDynamics fast(chain.size(), rows);
    TaskSpaceDynamics robust(chain.size(), rows, forced);
    const double floor = fast.options().min_eigenvalue;
    int fast_states = 0;
    for (int trial = 0; trial < 40; ++trial) {
      random_state(chain, d.get(), rng);
      dyn.update(*d);
      fast.update(dyn);
      robust.update(dyn);
      EXPECT_TRUE(robust.eigendecomposed());
      if (!fast.eigendecomposed()) {
        ++fast_states;
        EXPECT_EQ(fast.status(), TaskSpaceStatus::ok);
        EXPECT_GT(robust.eigenvalues()[0], floor);  // the certificate holds
      } else {
        EXPECT_LT(robust.eigenvalues()[0], floor * (1.0 + 1e-9));  // not taken needlessly
      }
      expect_same_outputs(fast, robust);
    }
    EXPECT_GT(fast_states, 20);
  }
}

TEST(TaskSpaceDynamics, EigenPathNearTheElbowSingularity) {
  // planar2 straightening its elbow: the fast path is used while far from the singularity, the
  // floored eigen path once the smallest eigenvalue drops below the floor
  const Chain chain(Robot::bundled("planar2"), "tip");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  TaskSpaceOptions forced;
  forced.always_eigendecompose = true;
  TaskSpaceDynamics fast(2, 2);
  TaskSpaceDynamics robust(2, 2, forced);
  Eigen::MatrixXd J(2, 2);
  bool saw_fast = false;
  bool saw_floor = false;
  for (double elbow = -0.6; elbow <= 1e-12; elbow += 0.01) {
    const Eigen::Vector2d q(0.3, elbow);
    chain.scatter(q, d->qpos);
    mju_zero(d->qvel, chain.robot().model().nv);
    mj_forward(&chain.robot().model(), d.get());
    dyn.update(*d);
    J << dyn.jacobian().row(0), dyn.jacobian().row(2);
    const TaskSpaceStatus status = fast.update(dyn.mass_matrix(), J);
    robust.update(dyn.mass_matrix(), J);
    if (status == TaskSpaceStatus::damped) {
      EXPECT_TRUE(fast.eigendecomposed());
      saw_floor = true;
    }
    saw_fast = saw_fast || !fast.eigendecomposed();
    expect_same_outputs(fast, robust);
  }
  EXPECT_TRUE(saw_fast);
  EXPECT_TRUE(saw_floor);
  EXPECT_EQ(fast.status(), TaskSpaceStatus::damped);
}

// Nᵀ·τ₀ of project_torque against the formed N (any status).
void expect_projection_matches_nullspace(const TaskSpaceDynamics& ts) {
  const Eigen::VectorXd tau0 = Eigen::VectorXd::LinSpaced(ts.dofs(), -2.0, 3.0);
  Eigen::VectorXd tau(ts.dofs());
  ts.project_torque(tau0, tau);
  const Eigen::VectorXd expected = ts.nullspace().transpose() * tau0;
  EXPECT_LE((tau - expected).norm(), 1e-9 * (1.0 + expected.norm()));
}

TEST(TaskSpaceDynamics, CompileTimeSizeKernelsMatchTheGeneralOnes) {
  // panda (n = 7) and ur5e (n = 6), 6 and 3 rows: the compile-time-size kernels against the
  // run-time-size ones, at random states, at a singular one (q = 0: the floor is active) and
  // with a floor raised above the smallest eigenvalue
  std::mt19937 rng(17);
  TaskSpaceOptions general;
  general.generic_kernels = true;
  for (const char* robot : {"panda", "ur5e"}) {
    SCOPED_TRACE(robot);
    const Chain chain(Robot::bundled(robot), "attachment_site");
    DataPtr d = chain.robot().make_data();
    ChainDynamics dyn(chain);
    for (const int rows : {6, 3}) {
      SCOPED_TRACE(rows);
      int damped = 0;
      for (int trial = 0; trial < 12; ++trial) {
        if (trial == 0) {
          chain.scatter(Eigen::VectorXd::Zero(chain.size()), d->qpos);
          mj_forward(&chain.robot().model(), d.get());
        } else {
          random_state(chain, d.get(), rng);
        }
        dyn.update(*d);
        TaskSpaceOptions fast_options;
        if (trial % 4 == 3) {
          // a floor between the eigenvalues: flooring on a regular state
          TaskSpaceDynamics probe(chain.size(), rows);
          probe.update(dyn);
          const Eigen::VectorXd& lambda = probe.eigenvalues();
          fast_options.min_eigenvalue = 0.5 * (lambda[0] + lambda[1]);
        }
        TaskSpaceOptions general_options = general;
        general_options.min_eigenvalue = fast_options.min_eigenvalue;
        TaskSpaceDynamics fast(chain.size(), rows, fast_options);
        TaskSpaceDynamics slow(chain.size(), rows, general_options);
        fast.update(dyn);
        slow.update(dyn);
        EXPECT_EQ(fast.eigendecomposed(), slow.eigendecomposed());
        expect_same_outputs(fast, slow);
        expect_projection_matches_nullspace(fast);
        Eigen::VectorXd tau_fast(chain.size()), tau_slow(chain.size());
        const Eigen::VectorXd tau0 = Eigen::VectorXd::Ones(chain.size());
        fast.project_torque(tau0, tau_fast);
        slow.project_torque(tau0, tau_slow);
        EXPECT_LE((tau_fast - tau_slow).norm(), 1e-9 * (1.0 + tau_slow.norm()));
        damped += fast.status() == TaskSpaceStatus::damped ? 1 : 0;
      }
      EXPECT_GE(damped, 3);  // q = 0 and the raised floors
    }
  }
}

TEST(TaskSpaceDynamics, FloorTestIsExactWhereTheTraceCertificateFails) {
  // a floor just under the smallest eigenvalue: trace(Λ) > 1/(2·floor), so the cheap certificate
  // cannot hold and the exact test (Cholesky of Λ⁻¹ − floor·I) decides: fast path, nothing
  // floored. Just over it: the eigen path floors. Both agree with the forced eigen path.
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  std::mt19937 rng(23);
  int checked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    random_state(chain, d.get(), rng);
    dyn.update(*d);
    for (const int rows : {6, 3}) {
      TaskSpaceDynamics probe(chain.size(), rows);
      if (probe.update(dyn) != TaskSpaceStatus::ok) continue;
      const double lowest = probe.eigenvalues()[0];
      ASSERT_GT(probe.lambda().trace(), 0.5 / (0.99 * lowest));
      for (const double factor : {0.99, 1.01}) {
        for (const bool generic : {false, true}) {
          TaskSpaceOptions options;
          options.min_eigenvalue = factor * lowest;
          options.generic_kernels = generic;
          TaskSpaceOptions forced = options;
          forced.always_eigendecompose = true;
          TaskSpaceDynamics fast(chain.size(), rows, options);
          TaskSpaceDynamics robust(chain.size(), rows, forced);
          fast.update(dyn);
          robust.update(dyn);
          EXPECT_EQ(fast.eigendecomposed(), factor > 1.0);
          EXPECT_EQ(fast.status(), factor > 1.0 ? TaskSpaceStatus::damped : TaskSpaceStatus::ok);
          expect_same_outputs(fast, robust);
          expect_projection_matches_nullspace(fast);
        }
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 6);
}

TEST(TaskSpaceDynamics, RankDeficientTaskIsDampedNotInfinite) {
  // a 6-row task on a 2-dof arm: J·M⁻¹·Jᵀ has rank 2
  const Chain chain(Robot::bundled("planar2"), "tip");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  TaskSpaceDynamics ts(2);
  mj_forward(&chain.robot().model(), d.get());
  dyn.update(*d);
  EXPECT_EQ(ts.update(dyn), TaskSpaceStatus::damped);
  EXPECT_TRUE(ts.lambda().allFinite());
  EXPECT_TRUE(ts.nullspace().allFinite());
  EXPECT_EQ(std::string(to_string(ts.status())), "damped");
}

TEST(TaskSpaceDynamics, RejectsBadSizesOptionsAndMass) {
  EXPECT_THROW(TaskSpaceDynamics(0), Error);
  EXPECT_THROW(TaskSpaceDynamics(7, 0), Error);
  EXPECT_THROW(TaskSpaceDynamics(7, 7), Error);
  EXPECT_THROW(TaskSpaceDynamics(7, 6, TaskSpaceOptions{0.0}), Error);
  EXPECT_THROW(TaskSpaceDynamics(7, 6, TaskSpaceOptions{NAN}), Error);
  TaskSpaceDynamics ts(2, 1);
  Eigen::Matrix2d M;
  M << 1.0, 2.0, 2.0, 1.0;  // indefinite
  EXPECT_EQ(ts.update(M, Eigen::RowVector2d(1.0, 0.0)), TaskSpaceStatus::not_positive_definite);
}

TEST(TaskSpaceDynamics, UpdateAllocatesNothing) {
  const Chain chain(Robot::bundled("panda"), "attachment_site");
  DataPtr d = chain.robot().make_data();
  ChainDynamics dyn(chain);
  TaskSpaceDynamics full(chain.size(), 6);
  TaskSpaceDynamics position(chain.size(), 3);
  std::mt19937 rng(9);
  random_state(chain, d.get(), rng);
  Eigen::VectorXd tau0 = Eigen::VectorXd::Ones(chain.size());
  Eigen::VectorXd tau(chain.size());
  const std::uint64_t calls = test::malloc_calls();
  for (int k = 0; k < 10; ++k) {
    dyn.update(*d);
    full.update(dyn);
    position.update(dyn);
    full.project_torque(tau0, tau);
    // the lazily filled caches allocate nothing either
    EXPECT_TRUE(full.nullspace().allFinite());
    EXPECT_TRUE(full.mass_inverse().allFinite());
    EXPECT_GT(full.condition(), 0.0);
  }
  EXPECT_EQ(test::malloc_calls() - calls, 0u);
  EXPECT_NE(full.status(), TaskSpaceStatus::not_positive_definite);
}

}  // namespace
}  // namespace mjarm
