#include "replay_scene.hpp"

#include <map>
#include <string>
#include <vector>

#include "base64.hpp"
#include "replay_cameras.hpp"
#include "replay_textures.hpp"

namespace mjarm::web_detail {
namespace {

const char* geom_type_name(int type) {
  switch (type) {
    case mjGEOM_PLANE:
      return "plane";
    case mjGEOM_HFIELD:
      return "hfield";
    case mjGEOM_SPHERE:
      return "sphere";
    case mjGEOM_CAPSULE:
      return "capsule";
    case mjGEOM_ELLIPSOID:
      return "ellipsoid";
    case mjGEOM_CYLINDER:
      return "cylinder";
    case mjGEOM_BOX:
      return "box";
    case mjGEOM_MESH:
      return "mesh";
    default:
      return "other";
  }
}

std::string name_of(const mjModel& m, int type, int id, const char* fallback) {
  const char* name = mj_id2name(&m, type, id);
  return (name != nullptr && name[0] != '\0') ? name : fallback + std::to_string(id);
}

nlohmann::json numbers(const double* values, int n) {
  nlohmann::json array = nlohmann::json::array();
  for (int i = 0; i < n; ++i) array.push_back(values[i]);
  return array;
}

nlohmann::json numbers(const float* values, int n) {
  nlohmann::json array = nlohmann::json::array();
  for (int i = 0; i < n; ++i) array.push_back(values[i]);
  return array;
}

// a mesh's texture coordinates per face corner (the page draws its faces unshared), as MuJoCo
// maps a texture on it; empty when the mesh has none
std::vector<float> mesh_face_texcoords(const mjModel& m, int mesh) {
  std::vector<float> uv;
  const int adr = m.mesh_texcoordadr[mesh];
  if (adr < 0) return uv;
  const int face = m.mesh_faceadr[mesh], nface = m.mesh_facenum[mesh];
  uv.reserve(static_cast<std::size_t>(6 * nface));
  for (int f = face; f < face + nface; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int t = adr + m.mesh_facetexcoord[3 * f + k];
      uv.push_back(m.mesh_texcoord[2 * t]);
      uv.push_back(m.mesh_texcoord[2 * t + 1]);
    }
  }
  return uv;
}

// a height field: its grid of elevations (row-major, 0 … 1 of its height) and its size (x, y,
// z_top, z_bottom: MuJoCo's hfield_size), drawn as mjr_uploadHField builds it
nlohmann::json hfield_json(const mjModel& m, int h) {
  const int nrow = m.hfield_nrow[h], ncol = m.hfield_ncol[h];
  const std::span<const float> data(
      m.hfield_data + m.hfield_adr[h],
      static_cast<std::size_t>(nrow) * static_cast<std::size_t>(ncol));
  return {{"name", name_of(m, mjOBJ_HFIELD, h, "hfield")},
          {"nrow", nrow},
          {"ncol", ncol},
          {"size", numbers(m.hfield_size + 4 * h, 4)},
          {"data", base64_floats(data)}};
}

nlohmann::json mesh_json(const mjModel& m, int mesh) {
  const int vert = m.mesh_vertadr[mesh], nvert = m.mesh_vertnum[mesh];
  const int face = m.mesh_faceadr[mesh], nface = m.mesh_facenum[mesh];
  const std::span<const float> vertices(m.mesh_vert + 3 * vert,
                                        static_cast<std::size_t>(3 * nvert));
  std::vector<unsigned> faces(static_cast<std::size_t>(3 * nface));
  for (std::size_t i = 0; i < faces.size(); ++i)
    faces[i] = static_cast<unsigned>(m.mesh_face[3 * face + static_cast<int>(i)]);
  return {{"name", name_of(m, mjOBJ_MESH, mesh, "mesh")},
          {"vert", base64_floats(vertices)},
          {"face", base64_uints(faces)}};
}

}  // namespace

bool geom_drawn(const mjModel& m, int g) {
  float rgba[4];
  geom_rgba(m, g, rgba);
  return m.geom_group[g] >= 0 && m.geom_group[g] < 3 && rgba[3] > 0.0f;
}

void geom_rgba(const mjModel& m, int g, float rgba[4]) {
  const float* own = m.geom_rgba + 4 * g;
  const int material = m.geom_matid[g];
  const bool own_is_default = own[0] == 0.5f && own[1] == 0.5f && own[2] == 0.5f && own[3] == 1.0f;
  const float* chosen = (material >= 0 && own_is_default) ? m.mat_rgba + 4 * material : own;
  for (int i = 0; i < 4; ++i) rgba[i] = chosen[i];
}

ReplayScene replay_scene(const mjModel& m) {
  ReplayScene scene;
  nlohmann::json& json = scene.json;
  json["bodies"] = nlohmann::json::array();
  for (int b = 0; b < m.nbody; ++b)
    json["bodies"].push_back(
        {{"name", name_of(m, mjOBJ_BODY, b, "body")}, {"parent", m.body_parentid[b]}});

  json["geoms"] = nlohmann::json::array();
  json["meshes"] = nlohmann::json::array();
  std::map<int, int> mesh_index;  // model mesh id → index in "meshes"
  json["hfields"] = nlohmann::json::array();
  std::map<int, int> hfield_index;  // model hfield id → index in "hfields"
  ReplayTextures textures(m);
  for (int g = 0; g < m.ngeom; ++g) {
    if (!geom_drawn(m, g)) continue;
    const int type = m.geom_type[g];
    int mesh = -1, hfield = -1;
    if (type == mjGEOM_MESH && m.geom_dataid[g] >= 0) {
      const int id = m.geom_dataid[g];
      auto [where, added] = mesh_index.emplace(id, static_cast<int>(json["meshes"].size()));
      if (added) json["meshes"].push_back(mesh_json(m, id));
      mesh = where->second;
    }
    if (type == mjGEOM_HFIELD && m.geom_dataid[g] >= 0) {
      const int id = m.geom_dataid[g];
      auto [where, added] = hfield_index.emplace(id, static_cast<int>(json["hfields"].size()));
      if (added) json["hfields"].push_back(hfield_json(m, id));
      hfield = where->second;
    }
    float rgba[4];
    geom_rgba(m, g, rgba);
    const int material = m.geom_matid[g];
    // the material's texture (2D or cube; MuJoCo draws a skybox texture on a geom as a cube), its
    // pixels embedded once
    const int texture =
        material >= 0 ? textures.use(m.mat_texid[material * mjNTEXROLE + mjTEXROLE_RGB]) : -1;
    // a mesh's own texture coordinates, when a texture is drawn on it (MuJoCo then uses them
    // instead of its planar mapping)
    if (mesh >= 0 && texture >= 0 && !json["meshes"][mesh].contains("texcoord")) {
      const std::vector<float> uv = mesh_face_texcoords(m, m.geom_dataid[g]);
      if (!uv.empty()) json["meshes"][mesh]["texcoord"] = base64_floats(uv);
    }
    // MuJoCo's default material when the geom has none
    const float specular = material >= 0 ? m.mat_specular[material] : 0.5f;
    const float shininess = material >= 0 ? m.mat_shininess[material] : 0.5f;
    const float emission = material >= 0 ? m.mat_emission[material] : 0.0f;
    json["geoms"].push_back(
        {{"name", name_of(m, mjOBJ_GEOM, g, "geom")},
         {"type", geom_type_name(type)},
         {"body", m.geom_bodyid[g]},
         {"size", numbers(m.geom_size + 3 * g, 3)},
         {"pos", numbers(m.geom_pos + 3 * g, 3)},
         {"quat", numbers(m.geom_quat + 4 * g, 4)},
         {"rgba", numbers(rgba, 4)},
         {"specular", specular},
         {"shininess", shininess},
         {"emission", emission},
         {"mesh", mesh},
         {"hfield", hfield},
         {"texture", texture},
         {"texrepeat", material >= 0 ? numbers(m.mat_texrepeat + 2 * material, 2)
                                     : nlohmann::json::array({1.0, 1.0})},
         {"texuniform", material >= 0 && m.mat_texuniform[material] != 0}});
    ++scene.drawn_geoms;
  }
  scene.meshes = static_cast<int>(json["meshes"].size());
  scene.hfields = static_cast<int>(json["hfields"].size());
  json["skybox"] = textures.skybox();
  json["textures"] = textures.json();
  scene.textures = static_cast<int>(json["textures"].size());

  json["cameras"] = nlohmann::json::array();
  int moving = 0;  // the cameras posed per frame (replay_camera_poses), in camera order
  for (int c = 0; c < m.ncam; ++c) {
    json["cameras"].push_back({{"name", name_of(m, mjOBJ_CAMERA, c, "camera")},
                               {"body", m.cam_bodyid[c]},
                               {"pos", numbers(m.cam_pos + 3 * c, 3)},
                               {"quat", numbers(m.cam_quat + 4 * c, 4)},
                               {"fovy", m.cam_fovy[c]},
                               {"track", camera_moves(m, c) ? moving++ : -1}});
  }
  scene.cameras = m.ncam;
  // the free bodies (the objects a task moves): their recorded qpos is their world pose, which
  // the page's tests compare with what it draws
  json["joints"] = nlohmann::json::array();
  for (int j = 0; j < m.njnt; ++j) {
    json["joints"].push_back(
        {{"name", name_of(m, mjOBJ_JOINT, j, "joint")}, {"body", m.jnt_bodyid[j]}});
  }
  json["free_joints"] = nlohmann::json::array();
  for (int j = 0; j < m.njnt; ++j) {
    if (m.jnt_type[j] != mjJNT_FREE) continue;
    json["free_joints"].push_back({{"joint", name_of(m, mjOBJ_JOINT, j, "joint")},
                                   {"body", name_of(m, mjOBJ_BODY, m.jnt_bodyid[j], "body")}});
  }
  json["center"] = numbers(m.stat.center, 3);
  json["extent"] = m.stat.extent;
  return scene;
}

}  // namespace mjarm::web_detail
