#pragma once
// Parts the scene generates itself: the arena and objects, as MJCF element trees (no text, so
// names and file paths need no escaping). Internal to the scene room.

#include <initializer_list>
#include <string>
#include <utility>

#include "mjarm/scene/scene_spec.hpp"
#include "mjcf_entity.hpp"

namespace mjarm::scene_detail {

/// An element with attributes.
XmlNode element(std::string tag,
                std::initializer_list<std::pair<std::string, std::string>> attrs = {});
/// Numbers as an attribute value.
std::string numbers_text(std::span<const double> values);

/// Floor, lights and optional table (unprefixed names: floor, key_light, table, ...).
Part arena_part(const ArenaSpec& spec);

/// An object's geom, centre site, and its free joint when @p free (unprefixed names: geom,
/// center, joint, mesh), to be mounted in a body at the object's pose.
/// @throws Error when its mesh file does not exist.
Part object_part(const ObjectSpec& spec, bool free);

/// A compound fixture's geoms (named after the pieces, at their poses) and its centre site
/// (unprefixed names), to be mounted in a body at the fixture's pose.
/// @throws Error when a piece's mesh file does not exist.
Part compound_part(const CompoundFixtureSpec& spec);

}  // namespace mjarm::scene_detail
