#pragma once
/// @file
/// The model as the replay page draws it: bodies, the drawn geoms (MuJoCo's visible groups 0–2,
/// alpha > 0) with their local poses, sizes and colours as MuJoCo chooses them, the meshes and
/// height fields they use, their textures and the skybox (replay_textures.hpp), the cameras, the
/// model's centre and extent.

#include <mujoco/mujoco.h>

#include <nlohmann/json.hpp>

namespace mjarm::web_detail {

struct ReplayScene {
  nlohmann::json json;  ///< bodies, geoms, meshes, hfields, textures, skybox, cameras, …
  int drawn_geoms = 0;
  int meshes = 0;
  int hfields = 0;
  int textures = 0;
  int cameras = 0;
};

/// True when MuJoCo's default visual options draw geom @p g: its group is one of the first three
/// (mjvOption's default geomgroup) and its colour is not fully transparent.
bool geom_drawn(const mjModel& m, int g);

/// The colour MuJoCo draws geom @p g in: its material's, unless the geom's own rgba differs from
/// the default (0.5, 0.5, 0.5, 1), which then wins (as mjv_addGeoms decides).
void geom_rgba(const mjModel& m, int g, float rgba[4]);

ReplayScene replay_scene(const mjModel& m);

}  // namespace mjarm::web_detail
