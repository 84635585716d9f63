// libFuzzer's entry point for one target (fuzz/fuzz_programs.cmake compiles it once per target, with
// MJARM_FUZZ_TARGET naming the target's function).
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return mjarm::fuzz::MJARM_FUZZ_TARGET(data, size);
}
