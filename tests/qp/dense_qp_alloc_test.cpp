// DenseQp::solve() and BoxQp::solve() allocate nothing (this is the qp room's one allocation-
// counting unit): every heap allocation of the process is counted while a
// solve runs. Eigen allocates through malloc, the standard library through operator new, so
// both are replaced in this translation unit (forwarding to glibc's own entry points).
// Under AddressSanitizer, which owns malloc and operator new, its allocation hook counts instead.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <limits>
#include <new>
#include <random>
#include <vector>

#include "mjarm/qp/box_qp.hpp"
#include "mjarm/qp/dense_qp.hpp"
#include "qp/qp_test_support.hpp"
#include "mjarm/address_sanitizer.hpp"

namespace {

std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void note_allocation() noexcept {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
}

}  // namespace

#if defined(MJARM_ADDRESS_SANITIZER)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void on_malloc(const volatile void*, std::size_t) { note_allocation(); }
void on_free(const volatile void*) {}
[[maybe_unused]] const int g_hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
}  // namespace
#elif defined(__GLIBC__)
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* ptr, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) noexcept {
  note_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  note_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* ptr, std::size_t size) noexcept {
  note_allocation();
  return __libc_realloc(ptr, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  note_allocation();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  note_allocation();
  *out = __libc_memalign(alignment, size);
  return *out == nullptr ? ENOMEM : 0;
}
}
#endif

#if !defined(MJARM_ADDRESS_SANITIZER) && defined(__GLIBC__)
// the global operator new replaced as well, on the same glibc heap
extern "C" void __libc_free(void* ptr);
void* operator new(std::size_t size) {
  note_allocation();
  if (void* p = __libc_malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  note_allocation();
  if (void* p = __libc_malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }
#endif

namespace mjarm::qp {
namespace {

using test::kInf;

// counts the allocations made by f()
template <class F>
long allocations_in(F&& f) {
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations.load();
}

TEST(DenseQpAllocation, CounterSeesAllocations) {
  // the hook must work, or a zero below would prove nothing
  const long eigen = allocations_in([] {
    Eigen::VectorXd v(100);
    v.setOnes();
    EXPECT_EQ(v.sum(), 100.0);
  });
  EXPECT_GE(eigen, 1);
  const long stl = allocations_in([] {
    auto* p = new std::vector<int>(10);
    delete p;
  });
  EXPECT_GE(stl, 1);
}

TEST(DenseQpAllocation, SolveAllocatesNothing) {
  std::mt19937 rng(41);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gauss = [&](int r, int c) {
    return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(r, c, [&] { return normal(rng); }));
  };
  for (const int n : {7, 30, 45}) {
    const int me = 2, mi = 4 * n;
    const Eigen::MatrixXd M = gauss(n, n);
    const Eigen::MatrixXd H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd g = 3.0 * gauss(n, 1);
    const Eigen::MatrixXd A = gauss(me, n), C = gauss(mi, n);
    const Eigen::VectorXd b = Eigen::VectorXd::Zero(me);
    const Eigen::VectorXd l = Eigen::VectorXd::Constant(mi, -1.0), u = Eigen::VectorXd::Ones(mi);
    const Eigen::VectorXd lb = Eigen::VectorXd::Constant(n, -0.8), ub = Eigen::VectorXd::Ones(n);
    const Eigen::VectorXd g2 = g + 0.03 * gauss(n, 1);
    const Eigen::VectorXd l_bad = Eigen::VectorXd::Constant(mi, 1e3);
    const Eigen::VectorXd u_bad = Eigen::VectorXd::Constant(mi, kInf);
    DenseQp qp(n, me, mi);
    qp.set_hessian(H);
    qp.set_gradient(g);
    qp.set_equalities(A, b);
    qp.set_inequalities(C, l, u);
    qp.set_bounds(lb, ub);
    SCOPED_TRACE(n);

    // cold solve right after construction, including the Cholesky factorization
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::solved); }), 0);
    // warm solve after a change of g and the kept factorization
    qp.set_gradient(g2);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::solved); }), 0);
    // warm solve that re-adds its working set after a new H
    qp.set_hessian(1.5 * H);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::solved); }), 0);
    // an infeasible problem (warm failure, cold retry)
    qp.set_inequality_limits(l_bad, u_bad);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::infeasible); }), 0);
    qp.set_inequality_limits(l, u);
    // the cold path and its iteration limit
    qp.settings().max_iterations = 2;
    EXPECT_EQ(allocations_in([&] { qp.solve(QpStart::cold); }), 0);
    qp.settings().max_iterations = 0;
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve(QpStart::cold).status, QpStatus::solved); }),
              0);
  }
}

TEST(BoxQpAllocation, SolveAllocatesNothing) {
  std::mt19937 rng(43);
  for (const int n : {1, 7, 12}) {
    SCOPED_TRACE(n);
    const Eigen::MatrixXd M = test::gaussian(rng, n, n);
    const Eigen::MatrixXd H = M.transpose() * M / n + Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd g = test::gaussian(rng, n, 1, 3.0),
                          g2 = g + test::gaussian(rng, n, 1, 0.1);
    const Eigen::VectorXd lb = Eigen::VectorXd::Constant(n, -0.5), ub = Eigen::VectorXd::Ones(n);
    BoxQp qp(n);
    qp.set_hessian(H);
    qp.set_gradient(g);
    qp.set_bounds(lb, ub);
    // cold, warm after a change of g, warm after a new H, the iteration limit, bad data
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve(QpStart::cold).status, QpStatus::solved); }),
              0);
    qp.set_gradient(g2);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::solved); }), 0);
    qp.set_hessian(1.5 * H);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::solved); }), 0);
    qp.settings().max_iterations = 1;
    EXPECT_EQ(allocations_in([&] { qp.solve(QpStart::cold); }), 0);
    qp.settings().max_iterations = 0;
    qp.set_bounds(ub, lb);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::invalid_input); }), 0);
    qp.set_bounds(lb, ub);
    qp.set_hessian(-H);
    EXPECT_EQ(allocations_in([&] { EXPECT_EQ(qp.solve().status, QpStatus::not_convex); }), 0);
  }
}

}  // namespace
}  // namespace mjarm::qp
