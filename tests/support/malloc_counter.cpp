// The one definition of the allocation counter (tests/ik/malloc_counter.hpp), compiled into the
// test executables of the rooms listed in tests/CMakeLists.txt (MJARM_MALLOC_COUNTER_ROOMS);
// their tests include "ik/malloc_counter.hpp" and call mjarm::test::malloc_calls(). Defining
// malloc twice in one executable would not link. It also checks the counter itself, in each of
// those executables.

#include "ik/malloc_counter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include "mjarm/address_sanitizer.hpp"

namespace {
std::atomic<std::uint64_t> g_support_malloc_calls{0};
}  // namespace

#if defined(MJARM_ADDRESS_SANITIZER)
// from the sanitizer runtime's allocator interface (GCC does not install its header)
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
namespace {
void count_support_allocation(const volatile void*, std::size_t) {
  g_support_malloc_calls.fetch_add(1, std::memory_order_relaxed);
}
void ignore_support_free(const volatile void*) {}  // the runtime wants both hooks
[[maybe_unused]] const int g_support_hook_installed =
    __sanitizer_install_malloc_and_free_hooks(count_support_allocation, ignore_support_free);
}  // namespace
#else
extern "C" void* __libc_malloc(std::size_t size) noexcept;
extern "C" void* malloc(std::size_t size) noexcept {
  g_support_malloc_calls.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
#endif

namespace mjarm::test {
std::uint64_t malloc_calls() noexcept {
  return g_support_malloc_calls.load(std::memory_order_relaxed);
}
}  // namespace mjarm::test

namespace {

TEST(MallocCounter, SeesEigenAndOperatorNew) {
  const std::uint64_t before = mjarm::test::malloc_calls();
  auto heap = std::make_unique<Eigen::VectorXd>(Eigen::VectorXd::Zero(100));
  EXPECT_GE(mjarm::test::malloc_calls() - before, 2u);  // the object and its coefficients
  const std::uint64_t after = mjarm::test::malloc_calls();
  (*heap)[0] = 1.0;
  EXPECT_EQ(mjarm::test::malloc_calls() - after, 0u);
}

}  // namespace
