#pragma once
// One MJCF part prepared for merging into a scene: loaded (3.x translated, asset paths
// absolute), normalized (radians, quaternions for euler/axisangle) and prefixed. Internal to the
// scene room.

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/mjcf_detail.hpp"

namespace mjarm::scene_detail {

using mjcf_detail::XmlNode;

/// A keyframe of one part, by joint and actuator name (so it survives merging).
struct PartKey {
  std::string name;
  std::vector<std::pair<std::string, std::vector<double>>> qpos;  ///< joint -> its coordinates
  std::vector<std::pair<std::string, double>> ctrl;               ///< actuator -> control
};

/// A part ready to merge.
struct Part {
  XmlNode root;                       ///< <mujoco> of the part
  std::vector<PartKey> keys;          ///< its keyframes (removed from root)
  std::vector<std::string> warnings;  ///< 3.x translation rewrites
  std::string source;                 ///< "robot 'left' (panda_hand.xml)" for messages
};

/// Loads the MJCF file @p file: translation for 2.2.2, then `normalize_part`, keyframes taken.
/// @throws Error naming the file when it is missing, malformed or untranslatable.
Part load_part(const std::filesystem::path& file, std::string source);

/// Parses generated MJCF text (radians) into a part.
Part parse_part(std::string_view xml, std::string source);

/// Rewrites angles into radians (joint range/ref/springref of hinge and ball joints, including
/// values inherited from default classes) and euler/axisangle orientations into quaternions,
/// following the part's own compiler angle and eulerseq; removes its <compiler> angle settings.
void normalize_part(XmlNode& root);

/// Prefixes every name and every name reference with `prefix + "/"`, names meshes, textures and
/// hfields that took their name from their file, turns the part's main default class into class
/// `prefix/main`, and gives every element that would have used the main class that class.
void prefix_part(Part& part, const std::string& prefix);

/// Removes floor planes and lights placed directly in the part's worldbody, and skybox textures.
void strip_arena(XmlNode& root);

/// The MuJoCo namespace an element's name lives in ("body", "joint", "actuator", ...), or ""
/// for elements without a name of their own. @p parent_tag is the tag of its parent element.
std::string name_kind(std::string_view tag, std::string_view parent_tag);

/// The child of @p root with tag @p tag, created (appended) when absent.
XmlNode& section(XmlNode& root, std::string_view tag);

}  // namespace mjarm::scene_detail
