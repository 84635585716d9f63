#pragma once
/// @file
/// MJARM_ADDRESS_SANITIZER is defined when the including unit compiles under AddressSanitizer.
/// GCC says so with __SANITIZE_ADDRESS__, clang only through __has_feature (which GCC 12 lacks).
/// Under ASan malloc is the sanitizer's: glibc's heap statistics read zero and glibc's malloc
/// hooks are not called, so heap figures and allocation counters ask the sanitizer instead.
#if defined(__SANITIZE_ADDRESS__)
#define MJARM_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MJARM_ADDRESS_SANITIZER 1
#endif
#endif
