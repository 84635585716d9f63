#pragma once
// Counts heap allocations of the test process, to prove that hot paths allocate nothing.
//
// Eigen allocates with std::malloc (not operator new), so the count is taken at malloc itself:
// tests/support/malloc_counter.cpp defines malloc (forwarding to glibc's __libc_malloc) in the
// executables of the rooms listed in tests/CMakeLists.txt (MJARM_MALLOC_COUNTER_ROOMS); under
// AddressSanitizer, whose allocator must stay in charge, it installs the sanitizer's malloc hook
// instead.
// operator new reaches malloc in libstdc++, so C++ allocations are counted too.

#include <cstdint>

namespace mjarm::test {

/// Heap allocations (malloc calls) made by the process so far.
std::uint64_t malloc_calls() noexcept;

}  // namespace mjarm::test
