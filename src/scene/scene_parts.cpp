#include "scene_parts.hpp"

#include <algorithm>
#include <filesystem>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"

namespace mjarm::scene_detail {

namespace {

void name_element(mjsElement* element, const std::string& name) {
  mjs_setName(element, name.c_str());
}

template <class To, std::size_t N>
void copy_values(To* to, const std::array<double, N>& from) {
  std::copy(from.begin(), from.end(), to);
}

mjtGeom geom_type(ObjectShape shape) {
  switch (shape) {
    case ObjectShape::box:
      return mjGEOM_BOX;
    case ObjectShape::sphere:
      return mjGEOM_SPHERE;
    case ObjectShape::cylinder:
      return mjGEOM_CYLINDER;
    case ObjectShape::capsule:
      return mjGEOM_CAPSULE;
    case ObjectShape::mesh:
      return mjGEOM_MESH;
  }
  return mjGEOM_BOX;
}

/// A geom for @p spec in @p body (with its mesh asset when it has a mesh file).
mjsGeom* add_object_geom(mjSpec& scene, mjsBody* body, const ObjectSpec& spec,
                         const std::string& geom_name, const std::string& mesh_name,
                         const std::string& mesh_file) {
  mjsGeom* geom = mjs_addGeom(body, nullptr);
  name_element(geom->element, geom_name);
  geom->type = geom_type(spec.shape);
  if (spec.shape == ObjectShape::mesh) {
    mjsMesh* mesh = mjs_addMesh(&scene, nullptr);
    name_element(mesh->element, mesh_name);
    if (spec.mesh_vertices.empty()) {
      mjs_setString(mesh->file, mesh_file.c_str());
    } else {
      // MJCF's vertex="...": single precision, as MuJoCo stores mesh vertices
      const std::vector<float> vertices(spec.mesh_vertices.begin(), spec.mesh_vertices.end());
      mjs_setFloat(mesh->uservert, vertices.data(), static_cast<int>(vertices.size()));
    }
    if (!spec.size.empty()) std::copy(spec.size.begin(), spec.size.end(), mesh->scale);
    mjs_setString(geom->meshname, mesh_name.c_str());
  } else {
    std::copy(spec.size.begin(), spec.size.end(), geom->size);
  }
  geom->mass = spec.mass;
  copy_values(geom->friction, spec.friction);
  copy_values(geom->rgba, spec.rgba);
  return geom;
}

/// The centre site of an object or fixture body, hidden in group 3.
void add_center_site(mjsBody* body, const std::string& name) {
  mjsSite* site = mjs_addSite(body, nullptr);
  name_element(site->element, name + "/center");
  site->size[0] = 0.002;
  site->group = 3;
}

mjsBody* add_posed_body(mjSpec& spec, const std::string& name, const std::array<double, 3>& pos,
                        const std::array<double, 4>& quat) {
  mjsBody* body = mjs_addBody(mjs_findBody(&spec, "world"), nullptr);
  name_element(body->element, name);
  copy_values(body->pos, pos);
  copy_values(body->quat, quat);
  return body;
}

}  // namespace

std::vector<NameKey> arena_names(const ArenaSpec& spec) {
  std::vector<NameKey> names{{"texture", "arena/sky"},       {"texture", "arena/floor_checker"},
                             {"material", "arena/floor"},    {"geom", "arena/floor"},
                             {"light", "arena/key_light"},   {"light", "arena/fill_light"}};
  if (spec.table) {
    names.insert(names.end(), {{"body", "arena/table"},
                               {"geom", "arena/table_top"},
                               {"geom", "arena/table_base"},
                               {"site", "arena/table_surface"}});
  }
  return names;
}

void add_arena(mjSpec& spec, const ArenaSpec& arena) {
  mjVisual& visual = spec.visual;
  std::fill_n(visual.headlight.ambient, 3, 0.3f);
  std::fill_n(visual.headlight.diffuse, 3, 0.5f);
  std::fill_n(visual.headlight.specular, 3, 0.0f);
  visual.global.offwidth = 1280;
  visual.global.offheight = 720;

  mjsTexture* sky = mjs_addTexture(&spec, nullptr);
  name_element(sky->element, "arena/sky");
  sky->type = mjTEXTURE_SKYBOX;
  sky->builtin = mjBUILTIN_GRADIENT;
  copy_values(sky->rgb1, std::array{0.55, 0.7, 0.85});
  copy_values(sky->rgb2, std::array{0.1, 0.12, 0.15});
  sky->width = 256;
  sky->height = 1536;
  mjsTexture* checker = mjs_addTexture(&spec, nullptr);
  name_element(checker->element, "arena/floor_checker");
  checker->type = mjTEXTURE_2D;
  checker->builtin = mjBUILTIN_CHECKER;
  copy_values(checker->rgb1, std::array{0.82, 0.84, 0.86});
  copy_values(checker->rgb2, std::array{0.62, 0.65, 0.68});
  checker->width = 256;
  checker->height = 256;
  checker->mark = mjMARK_EDGE;
  copy_values(checker->markrgb, std::array{0.5, 0.5, 0.5});
  mjsMaterial* material = mjs_addMaterial(&spec, nullptr);
  name_element(material->element, "arena/floor");
  mjs_setInStringVec(material->textures, mjTEXROLE_RGB, "arena/floor_checker");
  material->texrepeat[0] = material->texrepeat[1] = 8.0f;
  material->reflectance = 0.05f;

  mjsBody* world = mjs_findBody(&spec, "world");
  mjsGeom* floor = mjs_addGeom(world, nullptr);
  name_element(floor->element, "arena/floor");
  floor->type = mjGEOM_PLANE;
  copy_values(floor->size, std::array{arena.floor_half_size[0], arena.floor_half_size[1], 0.05});
  mjs_setString(floor->material, "arena/floor");
  const auto add_light = [&](const char* name, std::array<double, 3> pos,
                             std::array<double, 3> dir, float diffuse, bool shadow) {
    mjsLight* light = mjs_addLight(world, nullptr);
    name_element(light->element, name);
    light->type = mjLIGHT_DIRECTIONAL;
    copy_values(light->pos, pos);
    copy_values(light->dir, dir);
    std::fill_n(light->diffuse, 3, diffuse);
    light->castshadow = shadow;
  };
  add_light("arena/key_light", {0.0, 0.0, 4.0}, {0.0, 0.0, -1.0}, 0.7f, true);
  add_light("arena/fill_light", {2.0, -2.0, 3.0}, {-0.5, 0.5, -0.7}, 0.25f, false);
  if (!arena.table) return;

  const double h = arena.table_height;
  const double hx = arena.table_half_size[0];
  const double hy = arena.table_half_size[1];
  mjsBody* table = mjs_addBody(world, nullptr);
  name_element(table->element, "arena/table");
  copy_values(table->pos, std::array{arena.table_center[0], arena.table_center[1], 0.0});
  mjsGeom* top = mjs_addGeom(table, nullptr);
  name_element(top->element, "arena/table_top");
  top->type = mjGEOM_BOX;
  copy_values(top->size, std::array{hx, hy, 0.02});
  copy_values(top->pos, std::array{0.0, 0.0, h - 0.02});
  copy_values(top->friction, arena.table_friction);
  copy_values(top->rgba, std::array{0.55, 0.42, 0.3, 1.0});
  mjsGeom* base = mjs_addGeom(table, nullptr);
  name_element(base->element, "arena/table_base");
  base->type = mjGEOM_BOX;
  copy_values(base->size, std::array{0.8 * hx, 0.8 * hy, 0.5 * (h - 0.04)});
  copy_values(base->pos, std::array{0.0, 0.0, 0.5 * (h - 0.04)});
  copy_values(base->rgba, std::array{0.45, 0.34, 0.24, 1.0});
  mjsSite* surface = mjs_addSite(table, nullptr);
  name_element(surface->element, "arena/table_surface");
  copy_values(surface->pos, std::array{0.0, 0.0, h});
  surface->size[0] = 0.005;
  surface->group = 3;
}

std::string object_mesh_file(const ObjectSpec& spec) {
  if (spec.shape != ObjectShape::mesh || !spec.mesh_vertices.empty()) return {};
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
  return file.lexically_normal().string();
}

std::vector<NameKey> object_names(const ObjectSpec& spec, bool free) {
  std::vector<NameKey> names{{"body", spec.name},
                             {"geom", spec.name + "/geom"},
                             {"site", spec.name + "/center"}};
  if (free) names.emplace_back("joint", spec.name + "/joint");
  if (spec.shape == ObjectShape::mesh) names.emplace_back("mesh", spec.name + "/mesh");
  return names;
}

void add_object(mjSpec& spec, const ObjectSpec& object, bool free, const std::string& mesh_file) {
  mjsBody* body = add_posed_body(spec, object.name, object.pos, object.quat);
  if (free) name_element(mjs_addFreeJoint(body)->element, object.name + "/joint");
  add_object_geom(spec, body, object, object.name + "/geom", object.name + "/mesh", mesh_file);
  add_center_site(body, object.name);
}

std::vector<NameKey> compound_names(const CompoundFixtureSpec& spec) {
  std::vector<NameKey> names{{"body", spec.name}, {"site", spec.name + "/center"}};
  for (const ObjectSpec& piece : spec.pieces) {
    names.emplace_back("geom", spec.name + "/" + piece.name);
    if (piece.shape == ObjectShape::mesh)
      names.emplace_back("mesh", spec.name + "/" + piece.name + "_mesh");
  }
  return names;
}

void add_compound(mjSpec& spec, const CompoundFixtureSpec& fixture,
                  const std::vector<std::string>& mesh_files) {
  mjsBody* body = add_posed_body(spec, fixture.name, fixture.pos, fixture.quat);
  for (std::size_t i = 0; i < fixture.pieces.size(); ++i) {
    const ObjectSpec& piece = fixture.pieces[i];
    const std::string name = fixture.name + "/" + piece.name;
    mjsGeom* geom = add_object_geom(spec, body, piece, name, name + "_mesh", mesh_files[i]);
    copy_values(geom->pos, piece.pos);
    copy_values(geom->quat, piece.quat);
  }
  add_center_site(body, fixture.name);
}

void strip_arena(mjSpec& part) {
  std::vector<mjsElement*> doomed;
  mjsBody* world = mjs_findBody(&part, "world");
  for (mjsElement* e = mjs_firstChild(world, mjOBJ_GEOM, 0); e != nullptr;
       e = mjs_nextChild(world, e, 0))
    if (mjs_asGeom(e)->type == mjGEOM_PLANE) doomed.push_back(e);
  for (mjsElement* e = mjs_firstChild(world, mjOBJ_LIGHT, 0); e != nullptr;
       e = mjs_nextChild(world, e, 0))
    doomed.push_back(e);
  for (mjsElement* e = mjs_firstElement(&part, mjOBJ_TEXTURE); e != nullptr;
       e = mjs_nextElement(&part, e))
    if (mjs_asTexture(e)->type == mjTEXTURE_SKYBOX) doomed.push_back(e);
  for (mjsElement* e : doomed) mjs_delete(&part, e);
}

}  // namespace mjarm::scene_detail
