#include "fuzz_targets.hpp"
#include "mjarm/teleop/session_log.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

int fuzz_session(const std::uint8_t* data, std::size_t size) {
  return accept_or_refuse([&] { parse_session_log(as_text(data, size), "<fuzz>"); });
}

}  // namespace mjarm::fuzz
