#include "fuzz_targets.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "refusal.hpp"

namespace mjarm::fuzz {

int fuzz_scene(const std::uint8_t* data, std::size_t size) {
  // the bundled scenes sit in models/scenes and name their models relative to it
  return accept_or_refuse(
      [&] { parse_scene(as_text(data, size), Robot::models_dir() / "scenes", "<fuzz>"); });
}

}  // namespace mjarm::fuzz
