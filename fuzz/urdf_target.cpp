#include "fuzz_targets.hpp"
#include "mjarm/model/robot.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

// the same entry point as MJCF (the root element decides), with URDF seeds and dictionary
int fuzz_urdf(const std::uint8_t* data, std::size_t size) {
  return accept_or_refuse([&] { Robot::from_string(as_text(data, size), Robot::models_dir()); });
}

}  // namespace mjarm::fuzz
