#pragma once
/// @file
/// Name lookups that never return a silent -1: an unknown name throws an error that names its
/// kind, the name, the model and the closest existing names.

#include <mujoco/mujoco.h>

#include <string>
#include <string_view>
#include <vector>

#include "mjarm/closest_names.hpp"

namespace mjarm {

/// Human name of a MuJoCo object type ("joint", "site", ...).
const char* object_kind_name(mjtObj type) noexcept;

/// All names of objects of @p type in @p m, in id order (unnamed objects give "").
std::vector<std::string> object_names(const mjModel& m, mjtObj type);

/// Id of the object of @p type called @p name.
/// @throws Error "site 'tpi' not found in model 'planar2'; closest: tip" when absent.
int find_object(const mjModel& m, mjtObj type, std::string_view name);

/// Id of the object called @p name, or -1: for callers that try several kinds in turn.
int try_find_object(const mjModel& m, mjtObj type, std::string_view name) noexcept;

/// The model's name (its <mujoco model="..."> attribute).
std::string model_name(const mjModel& m);

}  // namespace mjarm
