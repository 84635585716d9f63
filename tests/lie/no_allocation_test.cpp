// Counts heap allocations made by the Lie-group functions: they work on fixed-size Eigen types
// only and must allocate nothing, so they can run inside control loops. The global operator
// new/new[] of this test executable are replaced by counting ones (this sees std containers
// and strings; dynamic-size Eigen types, which call malloc directly, are kept out of
// the lie room's API by using fixed-size types in every signature).

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>

#include "mjarm/lie/pose.hpp"
#include "mjarm/lie/pose_error.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/lie/se3.hpp"
#include "mjarm/lie/se3_jacobian.hpp"
#include "mjarm/lie/so3.hpp"
#include "mjarm/lie/so3_jacobian.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// GCC 12 flags free() on memory from the (replaced, malloc-backed) operator new as mismatched
// once both are inlined into one caller; here the pairing is intended
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
void* counted_allocation(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
}  // namespace

// array forms too: a sanitizer runtime may provide its own new[] that bypasses operator new
void* operator new(std::size_t size) { return counted_allocation(size); }
void* operator new[](std::size_t size) { return counted_allocation(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace mjarm {
namespace {

TEST(LieNoAllocation, EveryFunctionRunsWithoutHeapAllocation) {
  Vector6d xi, xi_dot;
  xi << 0.3, -0.2, 0.5, 0.4, -1.1, 0.7;
  xi_dot << 0.1, 0.2, -0.3, 0.5, 0.1, -0.2;
  const Eigen::Vector3d w = xi.tail<3>(), w_dot = xi_dot.tail<3>();
  double sink = 0.0;

  const long before = g_allocations.load();
  for (int i = 0; i < 10; ++i) {
    const Pose X = se3::exp(xi);
    const Pose Y = Pose::from_rpy(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.1, 0.2, 0.3));
    sink += (X * Y.inverse()).act(w).sum() + X.matrix().sum() + X.to_isometry().matrix().sum();
    sink += Pose::from_quaternion(w, Eigen::Vector4d(1, 0.1, 0.2, 0.3)).R.sum();
    sink += rpy_from_rotation(X.R).sum() + quaternion_from_rotation(X.R).sum();
    sink += so3::exp(w).sum() + so3::log(X.R).sum() + so3::angle(X.R);
    sink += so3::left_jacobian(w).sum() + so3::right_jacobian(w).sum();
    sink += so3::left_jacobian_inverse(w).sum() + so3::right_jacobian_inverse(w).sum();
    sink += so3::left_jacobian_derivative(w, w_dot).sum();
    sink += so3::left_jacobian_inverse_derivative(w, w_dot).sum();
    sink += se3::log(X).sum() + se3::hat(xi).sum() + se3::vee(se3::hat(xi)).sum();
    sink += se3::adjoint(X).sum() + se3::ad(xi).sum() + se3::coadjoint(X).sum();
    sink += se3::transform_twist(X, xi).sum() + se3::transform_wrench(X, xi).sum();
    sink += se3::left_jacobian(xi).sum() + se3::right_jacobian(xi).sum();
    sink += se3::left_jacobian_inverse(xi).sum() + se3::right_jacobian_inverse(xi).sum();
    sink += se3::left_jacobian_derivative(xi, xi_dot).sum();
    sink += se3::right_jacobian_derivative(xi, xi_dot).sum();
    sink += se3::left_jacobian_inverse_derivative(xi, xi_dot).sum();
    sink += se3::right_jacobian_inverse_derivative(xi, xi_dot).sum();
    const Vector6d e = log_error(X, Y);
    sink += e.sum() + log_error_world_aligned(X, Y).sum();
    sink += log_error_jacobian(e).sum() + log_error_world_aligned_jacobian(e).sum();
  }
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

TEST(LieNoAllocation, CounterSeesAllocations) {
  // guards the test above against a counter that never counts
  const long before = g_allocations.load();
  // stored through a volatile pointer so the compiler cannot elide the pair
  double* volatile a = new double[64];
  delete[] a;
  EXPECT_EQ(g_allocations.load() - before, 1);
  double* volatile b = new double(1.0);
  delete b;
  EXPECT_EQ(g_allocations.load() - before, 2);
}

}  // namespace
}  // namespace mjarm
