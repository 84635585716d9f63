#include "mjarm/kinematics/manipulability.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <utility>
#include <vector>

#include "kinematics/allocation_counter.hpp"
#include "mjarm/error.hpp"
#include "mjarm/kinematics/finite_difference.hpp"
#include "mjarm/kinematics/frame_state.hpp"
#include "mjarm/kinematics/workspace.hpp"
#include "support/reference_linear_algebra.hpp"
#include "support/test_models.hpp"
#include "mjarm/address_sanitizer.hpp"

// Allocation counting for the whole test_kinematics executable: malloc, calloc and realloc are
// interposed (libstdc++'s operator new and Eigen both allocate through malloc) and forwarded to
// glibc. Only the difference across a window is ever looked at. Under AddressSanitizer, whose
// runtime owns malloc, the global operator new is replaced instead.
namespace {
std::atomic<long> g_allocations{0};
long allocations() { return g_allocations.load(std::memory_order_relaxed); }
}  // namespace

long mjarm::test::heap_allocations() noexcept { return allocations(); }

#if defined(MJARM_ADDRESS_SANITIZER)
// GCC 12 cannot see that this operator new allocates with malloc, and warns on free below
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// the nothrow form too (std::stable_sort's buffer), or ASan's would be freed by the one below
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
#else
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* malloc(std::size_t size) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(pointer, size);
}
}
#endif

namespace mjarm {
namespace {

/// Two links of lengths 0.5 and 0.3 in the x-y plane, hinges about z: w = l1·l2·|sin q2|.
constexpr const char* kPlanar2 = R"(
<mujoco model="planar2_test">
  <compiler angle="radian"/>
  <worldbody>
    <body name="l1" pos="0 0 0.1">
      <joint name="q1" type="hinge" axis="0 0 1"/>
      <geom type="capsule" fromto="0 0 0 0.5 0 0" size="0.02"/>
      <body name="l2" pos="0.5 0 0">
        <joint name="q2" type="hinge" axis="0 0 1"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.02"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>
)";

Eigen::VectorXd random_q(const Chain& chain, std::mt19937_64& rng) {
  Eigen::VectorXd q(chain.size());
  JointSampler(chain).sample(rng, q);
  return q;
}

/// Central finite difference of w along each joint.
Eigen::VectorXd numeric_gradient(Manipulability& m, const Eigen::VectorXd& q, double h) {
  const auto w = [&m](const Eigen::VectorXd& x) { return m.evaluate(x).manipulability; };
  return finite_difference_jacobian(w, q, h).transpose();
}

/// Checks the analytic gradient against central differences at @p trials random configurations.
void expect_gradient_matches(const Chain& chain, JacobianBlock block, int trials,
                             std::uint64_t seed) {
  Manipulability m(chain, {.block = block});
  std::mt19937_64 rng(seed);
  Eigen::VectorXd g(chain.size());
  int checked = 0;
  for (int t = 0; t < trials; ++t) {
    const Eigen::VectorXd q = random_q(chain, rng);
    const ManipulabilityResult r = m.evaluate(q, g);
    // w has kinks where a singular value crosses zero: stay clear of them
    if (r.sigma_min < 1e-3) continue;
    const Eigen::VectorXd fd = numeric_gradient(m, q, 1e-6);
    const double scale = std::max(1.0, fd.norm());
    EXPECT_LT((g - fd).norm(), 1e-7 * scale)
        << "block " << to_string(block) << " trial " << t << "\nanalytic " << g.transpose()
        << "\nnumeric  " << fd.transpose();
    ++checked;
  }
  EXPECT_GT(checked, trials / 2);
}

class ManipulabilityTest : public ::testing::Test {
 protected:
  Robot tricky_ = Robot::from_string(test::kTrickyArm);
  Robot planar_ = Robot::from_string(kPlanar2);
};

TEST_F(ManipulabilityTest, JacobianDerivativeMatchesFiniteDifferences) {
  // the tool chain and an explicit, out-of-order list with an off-path joint
  const Chain chains[] = {Chain(tricky_, "tool"),
                          Chain(tricky_, {"j4", "j2", "off_path", "j3"}, "tool")};
  for (const Chain& chain : chains) {
    Manipulability m(chain);
    ChainKinematics kin(chain);
    std::mt19937_64 rng(21);
    const int n = chain.size();
    Matrix6Xd dJ(6, n), J(6, n);
    const auto jacobian = [&](const Eigen::VectorXd& x) {
      kin.update(x);
      kin.jacobian(J);
      return J;
    };
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd q = random_q(chain, rng);
      m.evaluate(q);
      // column i: vec(∂J/∂q_i), column-major
      const Eigen::MatrixXd fd = finite_difference_jacobian(jacobian, q);
      for (int i = 0; i < n; ++i) {
        m.jacobian_derivative(i, dJ);
        const Eigen::Map<const Matrix6Xd> dJ_fd(fd.col(i).data(), 6, n);
        EXPECT_LT((dJ - dJ_fd).norm(), 1e-8) << "joint " << chain.joint_names()[i];
      }
    }
  }
}

TEST_F(ManipulabilityTest, JacobianDerivativeReproducesBiasAcceleration) {
  // two algorithms: J̇·q̇ from the path walk equals Σ_k (∂J/∂q_k q̇_k) q̇
  const Chain chain(tricky_, {"j3", "j1", "off_path", "j5", "j2", "j4"}, "tool");
  Manipulability m(chain);
  std::mt19937_64 rng(8);
  const int n = chain.size();
  Matrix6Xd dJ(6, n);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_q(chain, rng);
    const Eigen::VectorXd qd = random_q(chain, rng);
    m.evaluate(q);
    Matrix6Xd Jdot = Matrix6Xd::Zero(6, n);
    for (int k = 0; k < n; ++k) {
      m.jacobian_derivative(k, dJ);
      Jdot += dJ * qd[k];
    }
    EXPECT_LT((Jdot * qd - m.kinematics().bias_acceleration(qd)).norm(), 1e-12);
  }
}

TEST_F(ManipulabilityTest, GradientMatchesFiniteDifferencesOnTrickyArm) {
  const Chain chain(tricky_, "tool");
  expect_gradient_matches(chain, JacobianBlock::full, 40, 1);
  expect_gradient_matches(chain, JacobianBlock::position, 40, 2);
  expect_gradient_matches(chain, JacobianBlock::orientation, 40, 3);
  // a chain whose column order differs from the path order
  const Chain shuffled(tricky_, {"j5", "j1", "j3", "j2", "j4"}, "tool");
  expect_gradient_matches(shuffled, JacobianBlock::full, 20, 4);
}

TEST_F(ManipulabilityTest, GradientMatchesFiniteDifferencesOnBundledArms) {
  const std::pair<const char*, const char*> arms[] = {{"panda", "attachment_site"},
                                                      {"ur5e", "attachment_site"},
                                                      {"iiwa14", "attachment_site"},
                                                      {"arm6", "grip"},
                                                      {"planar2", "tip"}};
  std::uint64_t seed = 5;
  for (const auto& [name, site] : arms) {
    SCOPED_TRACE(name);
    const Robot robot = Robot::bundled(name);
    const Chain chain(robot, site);
    expect_gradient_matches(chain, JacobianBlock::full, 20, seed++);
    expect_gradient_matches(chain, JacobianBlock::position, 20, seed++);
    // a planar arm turns about one axis only: its orientation block is singular everywhere
    if (chain.size() >= 3) expect_gradient_matches(chain, JacobianBlock::orientation, 10, seed++);
  }
}

TEST_F(ManipulabilityTest, ManipulabilityIsProductOfSingularValuesAndRootDeterminant) {
  const Chain chain(tricky_, "tool");
  DataPtr d = tricky_.make_data();
  std::mt19937_64 rng(9);
  Matrix6Xd J_mj(6, chain.size());
  for (JacobianBlock block :
       {JacobianBlock::full, JacobianBlock::position, JacobianBlock::orientation}) {
    Manipulability m(chain, {.block = block});
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd q = random_q(chain, rng);
      const ManipulabilityResult r = m.evaluate(q);
      EXPECT_NEAR(r.manipulability, m.singular_values().prod(), 1e-14);
      // an independent decomposition of MuJoCo's own Jacobian
      chain.scatter(q, d->qpos);
      mj_forward(&tricky_.model(), d.get());
      mujoco_frame_jacobian(chain, *d, J_mj);
      const Eigen::MatrixXd Jb =
          J_mj.middleRows(block == JacobianBlock::orientation ? 3 : 0, m.rows());
      // σ² are the eigenvalues of the smaller Gram matrix (descending, like the SVD's)
      const Eigen::MatrixXd gram = m.rows() <= chain.size() ? Eigen::MatrixXd(Jb * Jb.transpose())
                                                            : Eigen::MatrixXd(Jb.transpose() * Jb);
      const Eigen::VectorXd sigma =
          test::symmetric_eigenvalues(gram).reverse().cwiseMax(0.0).cwiseSqrt();
      EXPECT_LT((sigma - Eigen::VectorXd(m.singular_values())).norm(), 1e-10);
      // 5 joints: √det(JJᵀ) for 3-row blocks, √det(JᵀJ) for the 6-row one
      const double det = test::determinant(gram);
      EXPECT_NEAR(r.manipulability, std::sqrt(std::max(det, 0.0)), 1e-10);
      EXPECT_NEAR(r.condition_number, sigma(0) / sigma(sigma.size() - 1),
                  1e-6 * r.condition_number);
    }
  }
}

TEST_F(ManipulabilityTest, PlanarArmMatchesClosedFormAndDetectsStraightElbow) {
  const Chain chain(planar_, "tip");
  Manipulability m(chain, {.block = JacobianBlock::position});
  Eigen::VectorXd g(2);
  for (double q2 : {0.3, 1.2, 2.5, -0.7, -2.9}) {
    const Eigen::Vector2d q(0.4, q2);
    const ManipulabilityResult& r = m.evaluate(q, g);
    EXPECT_NEAR(r.manipulability, 0.5 * 0.3 * std::abs(std::sin(q2)), 1e-14);
    EXPECT_NEAR(g[0], 0.0, 1e-14);  // turning the whole arm changes nothing
    EXPECT_NEAR(g[1], 0.5 * 0.3 * std::cos(q2) * (q2 > 0 ? 1.0 : -1.0), 1e-13);
    EXPECT_EQ(r.status, SingularityStatus::regular);
  }
  // elbow straight: a direction is lost
  const ManipulabilityResult straight = m.evaluate(Eigen::Vector2d(0.4, 0.0), g);
  EXPECT_LT(straight.manipulability, 1e-15);
  EXPECT_EQ(straight.status, SingularityStatus::singular);
  EXPECT_TRUE(std::isinf(straight.condition_number));
  EXPECT_TRUE(g.allFinite());
  EXPECT_EQ(g.norm(), 0.0);
  // folded back on itself is singular too
  EXPECT_EQ(m.evaluate(Eigen::Vector2d(0.0, M_PI)).status, SingularityStatus::singular);
  // nearly straight: finite but large condition number
  const ManipulabilityResult near = m.evaluate(Eigen::Vector2d(0.4, 1e-4), g);
  EXPECT_EQ(near.status, SingularityStatus::near_singular);
  EXPECT_GT(near.condition_number, 1e3);
  EXPECT_TRUE(std::isfinite(near.condition_number));
  EXPECT_TRUE(g.allFinite());
  EXPECT_NEAR(g[1], 0.5 * 0.3 * std::cos(1e-4), 1e-12);  // the cofactor form needs no damping
}

TEST_F(ManipulabilityTest, KnownSingularitiesOfBundledArms) {
  // ur5e (DH joint angles): the elbow singularity at θ3 = 0 (upper arm and forearm in line) and
  // the wrist singularity at θ5 = 0 (wrist 1 and wrist 3 axes parallel)
  const Robot ur5e = Robot::bundled("ur5e");
  const Chain arm(ur5e, "attachment_site");
  Eigen::VectorXd q(6);
  q << 0.3, -1.2, 1.4, -1.0, -1.3, 0.4;  // a regular pose
  Manipulability m(arm);
  EXPECT_EQ(m.evaluate(q).status, SingularityStatus::regular);
  const double w_regular = m.result().manipulability;
  for (int joint : {2, 4}) {
    Eigen::VectorXd qs = q;
    qs[joint] = 0.0;
    const ManipulabilityResult r = m.evaluate(qs);
    EXPECT_LT(r.manipulability, 1e-12 * w_regular) << arm.joint_names()[joint];
    EXPECT_EQ(r.status, SingularityStatus::singular) << arm.joint_names()[joint];
    EXPECT_TRUE(std::isinf(r.condition_number));
  }
  // planar2 (0.4 m and 0.35 m links): w = l1·l2·|sin q_elbow| on the position block, 0 when
  // the elbow is straight
  const Robot planar = Robot::bundled("planar2");
  const Chain two(planar, "tip");
  Manipulability mp(two, {.block = JacobianBlock::position});
  for (double elbow : {-2.0, -1.0, -0.3, 0.4}) {
    EXPECT_NEAR(mp.evaluate(Eigen::Vector2d(0.2, elbow)).manipulability,
                0.4 * 0.35 * std::abs(std::sin(elbow)), 1e-14);
  }
  EXPECT_EQ(mp.evaluate(Eigen::Vector2d(0.2, 0.0)).status, SingularityStatus::singular);
  EXPECT_LT(mp.result().manipulability, 1e-15);
}

TEST_F(ManipulabilityTest, RejectsBadInput) {
  const Chain chain(tricky_, "tool");
  Manipulability m(chain);
  Eigen::VectorXd g(5);
  EXPECT_THROW(m.evaluate(Eigen::VectorXd::Zero(4)), Error);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(5);
  q[2] = std::nan("");
  EXPECT_THROW(m.evaluate(q), Error);
  Eigen::VectorXd short_gradient(3);
  EXPECT_THROW(m.evaluate(Eigen::VectorXd::Zero(5), short_gradient), Error);
  EXPECT_THROW(Manipulability(chain, {.singular_tolerance = 0.1, .near_singular_threshold = 0.01}),
               Error);
  Matrix6Xd dJ(6, 4);
  EXPECT_THROW(m.jacobian_derivative(0, dJ), Error);
}

TEST_F(ManipulabilityTest, EvaluateAllocatesNothing) {
  const Chain chain(tricky_, "tool");
  std::mt19937_64 rng(13);
  for (JacobianBlock block :
       {JacobianBlock::full, JacobianBlock::position, JacobianBlock::orientation}) {
    Manipulability m(chain, {.block = block});
    Eigen::VectorXd q = random_q(chain, rng);
    Eigen::VectorXd g(chain.size());
    m.evaluate(q, g);  // warm up
    const long before = allocations();
    double sink = 0.0;
    for (int k = 0; k < 50; ++k) {
      q[k % 5] += 0.01;
      sink += m.evaluate(q).manipulability;
      sink += m.evaluate(q, g).manipulability + g[0];
    }
    EXPECT_EQ(allocations() - before, 0) << to_string(block);
    EXPECT_TRUE(std::isfinite(sink));
  }
  // the window does see allocations when there are some
  const long before = allocations();
  const std::vector<double> heap(100, 1.0);
  EXPECT_GT(allocations() - before, 0);
  EXPECT_EQ(heap.size(), 100u);
}

}  // namespace
}  // namespace mjarm
