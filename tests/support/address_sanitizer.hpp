#pragma once
// MJARM_TEST_ASAN is defined when the unit compiles under AddressSanitizer: GCC says so with
// __SANITIZE_ADDRESS__, clang only through __has_feature (which GCC 12 lacks).
#if defined(__SANITIZE_ADDRESS__)
#define MJARM_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MJARM_TEST_ASAN 1
#endif
#endif
