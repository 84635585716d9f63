#include "scene_parts.hpp"

#include <algorithm>
#include <filesystem>
#include <iterator>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"

namespace mjarm::scene_detail {

XmlNode element(std::string tag, std::initializer_list<std::pair<std::string, std::string>> attrs) {
  XmlNode node;
  node.tag = std::move(tag);
  for (const auto& [k, v] : attrs) node.attrs.emplace_back(k, v);
  return node;
}

std::string numbers_text(std::span<const double> values) {
  return mjcf_detail::format_numbers(values);
}

Part arena_part(const ArenaSpec& spec) {
  validate(spec);
  Part part{element("mujoco", {{"model", "arena"}}), {}, {}, "arena"};
  XmlNode& root = part.root;

  XmlNode visual = element("visual");
  visual.children.push_back(
      element("headlight",
              {{"ambient", "0.3 0.3 0.3"}, {"diffuse", "0.5 0.5 0.5"}, {"specular", "0 0 0"}}));
  visual.children.push_back(element("global", {{"offwidth", "1280"}, {"offheight", "720"}}));
  root.children.push_back(std::move(visual));

  XmlNode asset = element("asset");
  asset.children.push_back(element("texture", {{"name", "sky"},
                                               {"type", "skybox"},
                                               {"builtin", "gradient"},
                                               {"rgb1", "0.55 0.7 0.85"},
                                               {"rgb2", "0.1 0.12 0.15"},
                                               {"width", "256"},
                                               {"height", "1536"}}));
  asset.children.push_back(element("texture", {{"name", "floor_checker"},
                                               {"type", "2d"},
                                               {"builtin", "checker"},
                                               {"rgb1", "0.82 0.84 0.86"},
                                               {"rgb2", "0.62 0.65 0.68"},
                                               {"width", "256"},
                                               {"height", "256"},
                                               {"mark", "edge"},
                                               {"markrgb", "0.5 0.5 0.5"}}));
  asset.children.push_back(element("material", {{"name", "floor"},
                                                {"texture", "floor_checker"},
                                                {"texrepeat", "8 8"},
                                                {"reflectance", "0.05"}}));
  root.children.push_back(std::move(asset));

  XmlNode world = element("worldbody");
  const double floor[3] = {spec.floor_half_size[0], spec.floor_half_size[1], 0.05};
  world.children.push_back(element("geom", {{"name", "floor"},
                                            {"type", "plane"},
                                            {"size", numbers_text(floor)},
                                            {"material", "floor"}}));
  world.children.push_back(element("light", {{"name", "key_light"},
                                             {"directional", "true"},
                                             {"pos", "0 0 4"},
                                             {"dir", "0 0 -1"},
                                             {"diffuse", "0.7 0.7 0.7"},
                                             {"castshadow", "true"}}));
  world.children.push_back(element("light", {{"name", "fill_light"},
                                             {"directional", "true"},
                                             {"pos", "2 -2 3"},
                                             {"dir", "-0.5 0.5 -0.7"},
                                             {"diffuse", "0.25 0.25 0.25"},
                                             {"castshadow", "false"}}));
  if (spec.table) {
    const double h = spec.table_height;
    const double hx = spec.table_half_size[0];
    const double hy = spec.table_half_size[1];
    const double center[3] = {spec.table_center[0], spec.table_center[1], 0.0};
    XmlNode table = element("body", {{"name", "table"}, {"pos", numbers_text(center)}});
    const double top_size[3] = {hx, hy, 0.02};
    const double top_pos[3] = {0.0, 0.0, h - 0.02};
    table.children.push_back(element("geom", {{"name", "table_top"},
                                              {"type", "box"},
                                              {"size", numbers_text(top_size)},
                                              {"pos", numbers_text(top_pos)},
                                              {"friction", numbers_text(spec.table_friction)},
                                              {"rgba", "0.55 0.42 0.3 1"}}));
    const double base_size[3] = {0.8 * hx, 0.8 * hy, 0.5 * (h - 0.04)};
    const double base_pos[3] = {0.0, 0.0, 0.5 * (h - 0.04)};
    table.children.push_back(element("geom", {{"name", "table_base"},
                                              {"type", "box"},
                                              {"size", numbers_text(base_size)},
                                              {"pos", numbers_text(base_pos)},
                                              {"rgba", "0.45 0.34 0.24 1"}}));
    const double surface[3] = {0.0, 0.0, h};
    table.children.push_back(element("site", {{"name", "table_surface"},
                                              {"pos", numbers_text(surface)},
                                              {"size", "0.005"},
                                              {"group", "3"}}));
    world.children.push_back(std::move(table));
  }
  root.children.push_back(std::move(world));
  return part;
}

namespace {

/// The `asset` element of @p part, added when it has none.
XmlNode& asset_of(Part& part) {
  auto asset = std::find_if(part.root.children.begin(), part.root.children.end(),
                            [](const XmlNode& n) { return n.tag == "asset"; });
  if (asset != part.root.children.end()) return *asset;
  part.root.children.push_back(element("asset"));
  return part.root.children.back();
}

/// The geom of @p spec called @p name (with its mesh asset in @p part when it is a mesh).
XmlNode object_geom(const ObjectSpec& spec, const std::string& name, Part& part) {
  XmlNode geom = element("geom", {{"name", name}, {"type", to_string(spec.shape)}});
  if (spec.shape == ObjectShape::mesh && !spec.mesh_vertices.empty()) {
    const std::string mesh_name = name == "geom" ? "mesh" : name + "_mesh";
    XmlNode mesh =
        element("mesh", {{"name", mesh_name}, {"vertex", numbers_text(spec.mesh_vertices)}});
    if (!spec.size.empty()) mesh.set("scale", numbers_text(spec.size));
    asset_of(part).children.push_back(std::move(mesh));
    geom.set("mesh", mesh_name);
  } else if (spec.shape == ObjectShape::mesh) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path file = fs::absolute(spec.mesh_file, ec);
    try {
      // a regular file within the asset limit, named for what it is when it is not
      check_user_file(ec ? fs::path(spec.mesh_file) : file, "mesh file", kMaxDataFileBytes);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + " (object '" + spec.name + "'" +
                  (file.string() == spec.mesh_file ? "" : ", given as '" + spec.mesh_file + "'") +
                  ")");
    }
    const std::string mesh_name = name == "geom" ? "mesh" : name + "_mesh";
    XmlNode mesh =
        element("mesh", {{"name", mesh_name}, {"file", file.lexically_normal().string()}});
    if (!spec.size.empty()) mesh.set("scale", numbers_text(spec.size));
    asset_of(part).children.push_back(std::move(mesh));
    geom.set("mesh", mesh_name);
  } else {
    geom.set("size", numbers_text(spec.size));
  }
  geom.set("mass", numbers_text(std::span<const double>(&spec.mass, 1)));
  geom.set("friction", numbers_text(spec.friction));
  geom.set("rgba", numbers_text(spec.rgba));
  return geom;
}

}  // namespace

Part object_part(const ObjectSpec& spec, bool free) {
  validate(spec);
  Part part{element("mujoco", {{"model", spec.name}}), {}, {}, "object '" + spec.name + "'"};
  XmlNode world = element("worldbody");
  if (free) world.children.push_back(element("freejoint", {{"name", "joint"}}));
  world.children.push_back(object_geom(spec, "geom", part));
  world.children.push_back(
      element("site", {{"name", "center"}, {"size", "0.002"}, {"group", "3"}}));
  part.root.children.push_back(std::move(world));
  return part;
}

Part compound_part(const CompoundFixtureSpec& spec) {
  validate(spec);
  Part part{element("mujoco", {{"model", spec.name}}), {}, {}, "fixture '" + spec.name + "'"};
  XmlNode world = element("worldbody");
  for (const ObjectSpec& piece : spec.pieces) {
    XmlNode geom = object_geom(piece, piece.name, part);
    geom.set("pos", numbers_text(piece.pos));
    geom.set("quat", numbers_text(piece.quat));
    world.children.push_back(std::move(geom));
  }
  world.children.push_back(
      element("site", {{"name", "center"}, {"size", "0.002"}, {"group", "3"}}));
  part.root.children.push_back(std::move(world));
  return part;
}

}  // namespace mjarm::scene_detail
