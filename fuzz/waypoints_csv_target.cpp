#include "fuzz_targets.hpp"
#include "mjarm/planning/waypoint_file.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

int fuzz_waypoints_csv(const std::uint8_t* data, std::size_t size) {
  return accept_or_refuse([&] { parse_waypoints_csv(as_text(data, size), "<fuzz>"); });
}

}  // namespace mjarm::fuzz
