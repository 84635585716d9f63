#include "fuzz_targets.hpp"
#include "mjarm/model/robot.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

int fuzz_mjcf(const std::uint8_t* data, std::size_t size) {
  // relative includes and meshes resolve in the bundled models' folder, as the seeds expect
  return accept_or_refuse([&] { Robot::from_string(as_text(data, size), Robot::models_dir()); });
}

}  // namespace mjarm::fuzz
