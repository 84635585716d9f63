#pragma once
// Counts heap allocations of the test_kinematics process, to prove that hot paths allocate
// nothing. manipulability_test.cpp interposes malloc/calloc/realloc (operator new under
// AddressSanitizer) and defines the counter; only the difference across a window is looked at.

namespace mjarm::test {

/// Heap allocations made by the process so far.
long heap_allocations() noexcept;

}  // namespace mjarm::test
