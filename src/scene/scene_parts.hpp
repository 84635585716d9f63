#pragma once
// Parts the scene makes itself — the arena, objects, compound fixtures — added to the scene's
// mjSpec element by element (mjs_addBody, mjs_addGeom, ...), with the names they take listed
// first so the scene can check them before anything changes; and the arena a part brings,
// which the scene removes. Internal to the scene room.

#include <mujoco/mujoco.h>

#include <string>
#include <utility>
#include <vector>

#include "mjarm/scene/scene_spec.hpp"

namespace mjarm::scene_detail {

/// A name in the scene: (kind, name), e.g. ("geom", "cube/geom").
using NameKey = std::pair<std::string, std::string>;

/// The names `add_arena` adds.
std::vector<NameKey> arena_names(const ArenaSpec& spec);
/// Adds floor, lights, skybox and optional table (names `arena/...`) and the arena's visual
/// settings (headlight, offscreen size) to @p spec.
void add_arena(mjSpec& spec, const ArenaSpec& arena);

/// The absolute mesh file of a mesh object, checked to be a regular file within the asset limit,
/// or "" for another shape or a mesh given by its vertices.
/// @throws Error naming the object when the file is missing or not a regular file.
std::string object_mesh_file(const ObjectSpec& spec);

/// The names `add_object` adds: body, geom, centre site, free joint (when @p free), mesh.
std::vector<NameKey> object_names(const ObjectSpec& spec, bool free);
/// Adds an object in a body at its pose in world, with a free joint when @p free; @p mesh_file
/// is `object_mesh_file(spec)`.
void add_object(mjSpec& spec, const ObjectSpec& object, bool free, const std::string& mesh_file);

/// The names `add_compound` adds: body, one geom (and mesh) per piece, centre site.
std::vector<NameKey> compound_names(const CompoundFixtureSpec& spec);
/// Adds a compound fixture: one static body at its pose, a geom per piece at the piece's pose in
/// it; @p mesh_files are `object_mesh_file` of each piece.
void add_compound(mjSpec& spec, const CompoundFixtureSpec& fixture,
                  const std::vector<std::string>& mesh_files);

/// Removes the floor planes and lights placed directly in @p part's world, and its skybox.
void strip_arena(mjSpec& part);

}  // namespace mjarm::scene_detail
