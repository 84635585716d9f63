#pragma once
/// @file
/// The closest names to a misspelt one, and the one wording every reader of mjarm uses for an
/// unknown word.

#include <string>
#include <string_view>
#include <vector>

namespace mjarm {

/// Up to @p count names from @p candidates closest to @p name (edit distance, then prefix).
std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates,
                                       std::size_t count = 3);

/// The error text for a word of a file that is not one of @p known, as every reader of mjarm's
/// files words it: "unknown key 'quaternoin' in waypoint 1; closest: quaternion; keys: position,
/// quaternion" (@p kind "key", @p where "waypoint 1"; without @p where: "unknown event 'jump';
/// closest: …"). The list is @p known in its order; the closest is by edit distance.
std::string unknown_name_message(std::string_view kind, std::string_view word,
                                 const std::vector<std::string>& known,
                                 std::string_view where = {});

}  // namespace mjarm
