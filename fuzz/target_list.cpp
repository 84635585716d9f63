#include <array>

#include "fuzz_targets.hpp"

namespace mjarm::fuzz {

std::span<const FuzzTarget> fuzz_targets() {
  static constexpr std::array kTargets{
      FuzzTarget{"mjcf", fuzz_mjcf},
      FuzzTarget{"urdf", fuzz_urdf},
      FuzzTarget{"scene", fuzz_scene},
      FuzzTarget{"waypoints_json", fuzz_waypoints_json},
      FuzzTarget{"waypoints_csv", fuzz_waypoints_csv},
      FuzzTarget{"session", fuzz_session},
      FuzzTarget{"viewer_script", fuzz_viewer_script},
      FuzzTarget{"recording", fuzz_recording},
  };
  return kTargets;
}

}  // namespace mjarm::fuzz
