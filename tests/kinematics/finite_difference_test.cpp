#include "mjarm/kinematics/finite_difference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "kinematics/allocation_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/chain_kinematics.hpp"
#include "mjarm/lie/se3.hpp"
#include "support/error_message.hpp"
#include "support/random_configurations.hpp"

namespace mjarm {
namespace {

/// f(x) = [sin(x0)·x1; x0·x1²; exp(x1)] and its Jacobian.
Eigen::Vector3d smooth_function(const Eigen::VectorXd& x) {
  return {std::sin(x[0]) * x[1], x[0] * x[1] * x[1], std::exp(x[1])};
}
Eigen::Matrix<double, 3, 2> smooth_jacobian(const Eigen::VectorXd& x) {
  Eigen::Matrix<double, 3, 2> J;
  J << std::cos(x[0]) * x[1], std::sin(x[0]), x[1] * x[1], 2 * x[0] * x[1], 0, std::exp(x[1]);
  return J;
}

/// Expects @p f to throw an Error whose message contains @p text.
template <class F>
void expect_fd_error(F&& f, const std::string& text) {
  const std::string message = test::error_of(f);
  EXPECT_NE(message.find(text), std::string::npos) << message;
}

/// The bundled arms and the frame each is driven by.
struct BundledArm {
  const char* model;
  const char* frame;
};
constexpr BundledArm kFdArms[] = {{"panda", "attachment_site"},
                                  {"ur5e", "attachment_site"},
                                  {"iiwa14", "attachment_site"},
                                  {"arm6", "grip"}};

TEST(FiniteDifference, VectorJacobianMatchesTheClosedForm) {
  const Eigen::Vector2d x(0.7, -1.3);
  const Eigen::MatrixXd J = finite_difference_jacobian(smooth_function, x);
  ASSERT_EQ(J.rows(), 3);
  ASSERT_EQ(J.cols(), 2);
  EXPECT_LT((J - smooth_jacobian(x)).cwiseAbs().maxCoeff(), 1e-9) << J;
  // a larger step is less accurate (truncation h²/6·|f'''|): the step is really used
  const Eigen::MatrixXd coarse = finite_difference_jacobian(smooth_function, x, 1e-2);
  EXPECT_GT((coarse - smooth_jacobian(x)).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((coarse - smooth_jacobian(x)).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(FiniteDifference, ScalarMatrixAndOutputArgumentForms) {
  const Eigen::Vector2d x(0.4, 0.9);
  // scalar: a 1 × n gradient row
  const auto scalar = [](const Eigen::VectorXd& v) { return v[0] * v[0] * v[1]; };
  const Eigen::MatrixXd g = finite_difference_jacobian(scalar, x);
  ASSERT_EQ(g.rows(), 1);
  EXPECT_NEAR(g(0, 0), 2 * 0.4 * 0.9, 1e-9);
  EXPECT_NEAR(g(0, 1), 0.16, 1e-9);
  // matrix valued: column i is vec(∂f/∂x_i), column-major
  const auto matrix = [](const Eigen::VectorXd& v) {
    Eigen::Matrix2d M;
    M << v[0], 2 * v[1], v[0] * v[1], 0;
    return M;
  };
  const Eigen::MatrixXd Jm = finite_difference_jacobian(matrix, x);
  ASSERT_EQ(Jm.rows(), 4);
  Eigen::Matrix<double, 4, 2> expected;
  expected << 1, 0, 0.9, 0.4, 0, 2, 0, 0;  // rows: M00, M10, M01, M11
  EXPECT_LT((Jm - expected).cwiseAbs().maxCoeff(), 1e-9) << Jm;
  // output argument, into a preallocated Jacobian
  const auto writes = [](const Eigen::VectorXd& v, Eigen::Ref<Eigen::VectorXd> y) {
    y = smooth_function(v);
  };
  Eigen::MatrixXd J(3, 2);
  FiniteDifferenceWorkspace workspace(2, 3);
  finite_difference_jacobian(writes, x, J, workspace);
  EXPECT_LT((J - smooth_jacobian(x)).cwiseAbs().maxCoeff(), 1e-9);
  // derivative of a function of one variable, scalar and vector valued
  EXPECT_NEAR(finite_difference_derivative([](double t) { return std::sin(t); }, 0.3),
              std::cos(0.3), 1e-9);
  const Eigen::Vector2d d = finite_difference_derivative(
      [](double t) { return Eigen::Vector2d(t * t, std::exp(t)); }, 1.5);
  EXPECT_LT((d - Eigen::Vector2d(3.0, std::exp(1.5))).norm(), 1e-8);
}

TEST(FiniteDifference, PoseJacobianMatchesTheArmsInEveryFrame) {
  // the analytic Jacobians of ChainKinematics against the SE(3)-log differences
  std::mt19937 rng(7);
  for (const BundledArm& arm : kFdArms) {
    const Robot robot = Robot::bundled(arm.model);
    const Chain chain(robot, arm.frame);
    ChainKinematics kin(chain);
    const auto fk = [&kin](const Eigen::VectorXd& q) { return kin.update(q); };
    const int n = chain.size();
    Matrix6Xd J(6, n), fd(6, n);
    FiniteDifferenceWorkspace workspace(n, 6);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = test::random_q(chain, rng);
      for (JacobianFrame frame :
           {JacobianFrame::world_aligned, JacobianFrame::local, JacobianFrame::world}) {
        finite_difference_pose_jacobian(fk, q, fd, workspace, frame);
        kin.update(q);
        kin.jacobian(J, frame);
        EXPECT_LT((J - fd).cwiseAbs().maxCoeff(), 1e-8)
            << arm.model << " frame " << static_cast<int>(frame) << "\n"
            << J << "\n"
            << fd;
      }
    }
  }
}

TEST(FiniteDifference, PoseJacobianOfAKnownMotion) {
  // X(x) = exp(x0·ξ)·X0: the world (spatial) Jacobian is ξ, the local one Ad(X⁻¹)·ξ
  Vector6d xi;
  xi << 0.3, -0.2, 0.5, 0.4, 1.1, -0.7;
  const Pose X0 = se3::exp((Vector6d() << 1, 2, 3, 0.2, -0.5, 0.9).finished());
  const auto motion = [&](const Eigen::VectorXd& x) { return se3::exp(x[0] * xi) * X0; };
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 0.25);
  const Pose X = motion(x);
  const Matrix6Xd world = finite_difference_pose_jacobian(motion, x, JacobianFrame::world);
  const Matrix6Xd local = finite_difference_pose_jacobian(motion, x, JacobianFrame::local);
  const Matrix6Xd aligned = finite_difference_pose_jacobian(motion, x);
  EXPECT_LT((world.col(0) - xi).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((local.col(0) - se3::adjoint(X.inverse()) * xi).cwiseAbs().maxCoeff(), 1e-9);
  // world-aligned: [ṗ; ω] with ṗ = v + ω × p
  const Eigen::Vector3d w = xi.tail<3>();
  EXPECT_LT((aligned.col(0).head<3>() - (xi.head<3>() + w.cross(X.p))).norm(), 1e-9);
  EXPECT_LT((aligned.col(0).tail<3>() - w).norm(), 1e-9);
}

TEST(FiniteDifference, PreallocatedFormsAllocateNothing) {
  const Robot robot = Robot::bundled("panda");
  const Chain chain(robot, "attachment_site");
  ChainKinematics kin(chain);
  const int n = chain.size();
  const Eigen::VectorXd q = chain.center();
  Matrix6Xd J(6, n);
  Eigen::MatrixXd Jv(3, n);
  FiniteDifferenceWorkspace workspace(n, 3);
  const auto fk = [&kin](const Eigen::VectorXd& x) -> const Pose& { return kin.update(x); };
  const auto position = [&kin](const Eigen::VectorXd& x, Eigen::Ref<Eigen::VectorXd> y) {
    y = kin.update(x).p;
  };
  const auto fixed = [&kin](const Eigen::VectorXd& x) -> Eigen::Vector3d {
    return kin.update(x).p;
  };
  const long before = test::heap_allocations();
  finite_difference_pose_jacobian(fk, q, J, workspace, JacobianFrame::local);
  finite_difference_jacobian(position, q, Jv, workspace);
  finite_difference_jacobian(fixed, q, Jv, workspace);
  EXPECT_EQ(test::heap_allocations() - before, 0);
  // and they computed: the position rows against the analytic world-aligned Jacobian
  kin.update(q);
  Matrix6Xd J_aligned(6, n);
  kin.jacobian(J_aligned);
  EXPECT_LT((Jv - J_aligned.topRows(3)).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(FiniteDifference, BadInputIsNamed) {
  const Eigen::Vector2d x(0.1, 0.2);
  Eigen::MatrixXd J(3, 2);
  FiniteDifferenceWorkspace workspace;
  const auto f = [](const Eigen::VectorXd& v) { return smooth_function(v); };
  expect_fd_error([&] { finite_difference_jacobian(f, x, J, workspace, 0.0); },
                  "step must be finite and > 0, got 0");
  expect_fd_error([&] { finite_difference_jacobian(f, x, J, workspace, std::nan("")); }, "got nan");
  expect_fd_error(
      [&] { finite_difference_jacobian(f, Eigen::Vector2d(0.1, INFINITY), J, workspace); },
      "x[1] must be finite, got inf");
  Eigen::MatrixXd wrong(3, 3);
  expect_fd_error([&] { finite_difference_jacobian(f, x, wrong, workspace); },
                  "output is 3x3, expected mx2");
  Eigen::MatrixXd too_many_rows(4, 2);
  expect_fd_error([&] { finite_difference_jacobian(f, x, too_many_rows, workspace); },
                  "returned 3 values where the Jacobian has 4 rows");
  expect_fd_error([&] { finite_difference_jacobian(f, Eigen::Vector2d(1e12, 0.0)); },
                  "step 1e-06 vanishes at x[0] = 1e+12");
  Matrix6Xd pose_J(6, 3);
  const auto pose = [](const Eigen::VectorXd& v) { return se3::exp(Vector6d::Constant(v[0])); };
  expect_fd_error([&] { finite_difference_pose_jacobian(pose, x, pose_J, workspace); },
                  "pose Jacobian output is 6x3, expected 6x2");
  expect_fd_error([&] { finite_difference_derivative([](double t) { return t; }, NAN); },
                  "must be finite");
}

}  // namespace
}  // namespace mjarm
