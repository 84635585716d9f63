#include "urdf_assets.hpp"

#include <tinyxml2.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"

namespace mjarm {

namespace {

namespace fs = std::filesystem;

// MuJoCo's <mujoco><compiler> extension inside a URDF
struct UrdfCompiler {
  fs::path meshdir;
  bool strippath = true;
};

UrdfCompiler urdf_compiler(const tinyxml2::XMLElement& robot) {
  UrdfCompiler c;
  for (const auto* m = robot.FirstChildElement("mujoco"); m; m = m->NextSiblingElement("mujoco")) {
    for (const auto* e = m->FirstChildElement("compiler"); e;
         e = e->NextSiblingElement("compiler")) {
      if (const char* v = e->Attribute("meshdir")) c.meshdir = v;
      if (const char* v = e->Attribute("strippath")) c.strippath = std::string(v) != "false";
    }
  }
  return c;
}

void check_meshes(const tinyxml2::XMLElement& e, const UrdfCompiler& c, const fs::path& base,
                  const std::string& source) {
  for (const auto* child = e.FirstChildElement(); child; child = child->NextSiblingElement()) {
    const char* file =
        std::string_view(child->Name()) == "mesh" ? child->Attribute("filename") : nullptr;
    if (file != nullptr && *file != '\0') {
      const fs::path name = c.strippath ? fs::path(file).filename() : fs::path(file);
      const fs::path path = name.is_absolute() ? name : base / c.meshdir / name;
      std::error_code ec;
      if (fs::exists(fs::symlink_status(path, ec))) {
        try {
          check_user_file(path, "mesh file", kMaxDataFileBytes);
        } catch (const Error& err) {
          throw Error("URDF " + source + ": mesh (line " + std::to_string(child->GetLineNum()) +
                      "): " + err.what());
        }
      }
    }
    check_meshes(*child, c, base, source);
  }
}

}  // namespace

void check_urdf_assets(std::string_view xml, const fs::path& base_dir, const std::string& source) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) return;  // MuJoCo reports it
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr) return;
  check_meshes(*robot, urdf_compiler(*robot), base_dir, source);
}

}  // namespace mjarm
