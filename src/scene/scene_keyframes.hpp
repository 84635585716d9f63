#pragma once
// A scene's keyframes: each attached part brings its own ("left/home", "right/home"), and the
// compiled scene has one key per name holding every part's values at its own joints and actuators.

#include <mujoco/mujoco.h>

#include <string>
#include <utility>
#include <vector>

#include "mjarm/model/mjcf_spec.hpp"
#include "mjarm/model/robot.hpp"

namespace mjarm::scene_detail {

/// A keyed part: its keyframes are combined with the other parts' by name at compile time.
struct PartKeys {
  std::string prefix;                  ///< "left/"
  std::vector<std::string> keys;       ///< the part's own key names ("home")
  std::vector<std::string> joints;     ///< its joints, prefixed
  std::vector<std::string> actuators;  ///< its actuators, prefixed
};

/// A copy of @p spec compiled into a Robot (errors name scene @p scene_name), the keyframes of
/// the @p keyed parts combined by name: one key per name, each part's values at its own joints and
/// actuators, qpos0 and 0 elsewhere; the parts' prefixed keys are gone from the copy.
std::pair<SpecPtr, Robot> compile_combining_keys(const mjSpec& spec, const std::string& scene_name,
                                                 const std::vector<std::string>& warnings,
                                                 const std::vector<PartKeys>& keyed);

}  // namespace mjarm::scene_detail
