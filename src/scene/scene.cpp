#include "mjarm/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"
#include "mjcf_entity.hpp"
#include "scene_parts.hpp"

namespace mjarm {

namespace fs = std::filesystem;
using scene_detail::element;
using scene_detail::numbers_text;
using scene_detail::Part;
using scene_detail::PartKey;
using scene_detail::XmlNode;

namespace {

// root sections in MJCF order; all exist from the start, so pointers into the worldbody stay valid
constexpr const char* kSections[] = {"compiler", "option", "size",     "visual",    "statistic",
                                     "default",  "custom", "asset",    "worldbody", "contact",
                                     "equality", "tendon", "actuator", "sensor"};

// global settings merged attribute by attribute: the first part that sets one keeps it
bool is_global_section(std::string_view tag) {
  return tag == "option" || tag == "size" || tag == "visual" || tag == "statistic";
}

using NameKey = std::pair<std::string, std::string>;  // (kind, name)

void collect_names(const XmlNode& node, std::vector<NameKey>& out) {
  for (const auto& c : node.children) {
    const std::string kind = scene_detail::name_kind(c.tag, node.tag);
    const std::string* n = c.find(c.tag == "default" ? "class" : "name");
    if (!kind.empty() && n && !n->empty()) out.emplace_back(kind, *n);
    collect_names(c, out);
  }
}

void merge_first_wins(XmlNode& into, const XmlNode& from, const std::string& path,
                      const std::string& source, std::vector<std::string>& warnings) {
  for (const auto& [key, value] : from.attrs) {
    const std::string* have = into.find(key);
    if (!have) {
      into.set(key, value);
    } else if (*have != value) {
      warnings.push_back(source + ": " + path + " " + key + "=\"" + value +
                         "\" not taken; the scene keeps \"" + *have + "\"");
    }
  }
  for (const auto& c : from.children) {
    auto it = std::find_if(into.children.begin(), into.children.end(),
                           [&](const XmlNode& e) { return e.tag == c.tag; });
    if (it == into.children.end()) {
      into.children.push_back(c);
    } else {
      merge_first_wins(*it, c, path + "/" + c.tag, source, warnings);
    }
  }
}

XmlNode* find_in(XmlNode& node, std::string_view kind, std::string_view name) {
  for (auto& c : node.children) {
    if (scene_detail::name_kind(c.tag, node.tag) == kind) {
      const std::string* n = c.find(c.tag == "default" ? "class" : "name");
      if (n && *n == name) return &c;
    }
    if (XmlNode* found = find_in(c, kind, name)) return found;
  }
  return nullptr;
}

XmlNode* parent_of(XmlNode& node, const XmlNode* child) {
  for (auto& c : node.children) {
    if (&c == child) return &node;
    if (XmlNode* found = parent_of(c, child)) return found;
  }
  return nullptr;
}

std::string list(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

bool looks_like_path(const std::string& s) {
  const fs::path p(s);
  return p.has_extension() || p.has_parent_path();
}

std::vector<std::string> xml_stems(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml")
      names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// a bundled name in dir, or a file path
fs::path resolve_model(const std::string& model, const fs::path& dir, const char* what) {
  if (looks_like_path(model)) return model;
  const fs::path file = dir / (model + ".xml");
  std::error_code ec;
  if (fs::is_regular_file(file, ec)) return file;
  const auto names = xml_stems(dir);
  std::string message = "unknown " + std::string(what) + " '" + model + "'";
  const auto close = closest_names(model, names, 3);
  if (!close.empty()) message += "; closest: " + list(close);
  throw Error(message + "; bundled " + what + "s in " + dir.string() + ": " + list(names));
}

}  // namespace

struct Scene::Impl {
  std::string name;
  XmlNode root;
  std::map<NameKey, std::string> owners;  // every name in the scene -> the part that brought it
  std::set<std::string> robots;
  bool arena = false;
  std::vector<PartKey> keys;
  std::vector<std::string> local_key_names;  // keys[i]'s name inside its part
  std::vector<std::string> warnings;

  XmlNode& sec(std::string_view tag) { return scene_detail::section(root, tag); }

  /// The element, or an Error naming the closest existing names of that kind.
  XmlNode& require(std::string_view kind, std::string_view element_name, const std::string& why) {
    if (XmlNode* e = find_in(root, kind, element_name)) return *e;
    std::vector<std::string> all;
    for (const auto& [key, owner] : owners)
      if (key.first == kind) all.push_back(key.second);
    std::string message = why + ": no " + std::string(kind) + " named '" +
                          std::string(element_name) + "' in scene '" + name + "'";
    const auto close = closest_names(element_name, all, 3);
    if (!close.empty()) message += "; closest: " + list(close);
    throw Error(message);
  }

  void check_free(const std::vector<NameKey>& names, const std::string& source) const {
    std::set<NameKey> seen;
    for (const auto& key : names) {
      const auto it = owners.find(key);
      if (it != owners.end()) {
        throw Error("name clash in scene '" + name + "': " + key.first + " '" + key.second +
                    "' of " + source + " is already defined by " + it->second);
      }
      if (!seen.insert(key).second) {
        throw Error("name clash in scene '" + name + "': " + source + " defines " + key.first +
                    " '" + key.second + "' twice");
      }
    }
  }

  void claim(const std::vector<NameKey>& names, const std::string& source) {
    for (const auto& key : names) owners.emplace(key, source);
  }

  /// Merges a prefixed part: its world content goes into @p mount (added to @p parent) or,
  /// without a mount, straight into @p parent. Checks everything before changing anything.
  void merge(Part part, XmlNode& parent, std::optional<XmlNode> mount,
             const std::vector<std::string>& local_keys) {
    std::vector<NameKey> names;
    if (mount) names.emplace_back("body", *mount->find("name"));
    collect_names(part.root, names);
    check_free(names, part.source);
    XmlNode& compiler = root.children.front();
    for (const auto& c : part.root.children) {
      if (c.tag != "compiler") continue;
      for (const auto& [key, value] : c.attrs) {
        if (key == "angle" || key == "autolimits") continue;
        const std::string* have = compiler.find(key);
        if (have && *have != value) {
          throw Error(part.source + ": compiler " + key + "=\"" + value +
                      "\" conflicts with the scene's " + key + "=\"" + *have +
                      "\" (MuJoCo 2.2.2 has one compiler setting per model)");
        }
      }
    }
    // world content first: `parent` points into the worldbody
    for (auto& c : part.root.children) {
      if (c.tag != "worldbody") continue;
      if (mount) {
        for (auto& e : c.children) mount->children.push_back(std::move(e));
      } else {
        for (auto& e : c.children) parent.children.push_back(std::move(e));
      }
    }
    if (mount) parent.children.push_back(std::move(*mount));
    for (auto& c : part.root.children) {
      if (c.tag == "worldbody") continue;
      if (c.tag == "compiler") {
        for (const auto& [key, value] : c.attrs)
          if (key != "angle" && key != "autolimits") compiler.set(key, value);
      } else if (is_global_section(c.tag)) {
        merge_first_wins(sec(c.tag), c, c.tag, part.source, warnings);
      } else if (c.tag == "default") {
        sec("default").children.push_back(std::move(c));
      } else {
        XmlNode& into = sec(c.tag);
        for (auto& e : c.children) into.children.push_back(std::move(e));
      }
    }
    for (std::size_t i = 0; i < part.keys.size(); ++i) {
      keys.push_back(std::move(part.keys[i]));
      local_key_names.push_back(i < local_keys.size() ? local_keys[i] : keys.back().name);
    }
    for (const auto& w : part.warnings) warnings.push_back(part.source + ": " + w);
    claim(names, part.source);
  }

  /// Prefixes and merges a part, remembering its keys' own names for combining.
  void add_part(Part part, const std::string& prefix, XmlNode& parent,
                std::optional<XmlNode> mount) {
    std::vector<std::string> local;
    for (const auto& k : part.keys) local.push_back(k.name);
    scene_detail::prefix_part(part, prefix);
    merge(std::move(part), parent, std::move(mount), local);
  }

  XmlNode& body_or_world(const std::string& body, const std::string& why) {
    if (body.empty()) return sec("worldbody");
    return require("body", body, why);
  }

  /// Checks a name an element added by hand would take.
  void check_single(const std::string& kind, const std::string& element_name,
                    const std::string& source) const {
    check_free({{kind, element_name}}, source);
  }
};

Scene::Scene(std::string name) : impl_(std::make_unique<Impl>()) {
  impl_->name = std::move(name);
  impl_->root = element("mujoco", {{"model", impl_->name}});
  for (const char* tag : kSections) impl_->root.children.push_back(element(tag));
  XmlNode& compiler = impl_->root.children.front();
  compiler.set("angle", "radian");
  compiler.set("autolimits", "true");
}

Scene::~Scene() = default;
Scene::Scene(const Scene& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
Scene& Scene::operator=(const Scene& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
Scene::Scene(Scene&& other) noexcept = default;
Scene& Scene::operator=(Scene&& other) noexcept = default;

const std::string& Scene::name() const noexcept { return impl_->name; }
const std::vector<std::string>& Scene::warnings() const noexcept { return impl_->warnings; }

std::vector<std::string> Scene::bundled_grippers() {
  return xml_stems(Robot::models_dir() / "grippers");
}

void Scene::add_arena(const ArenaSpec& arena) {
  if (impl_->arena) throw Error("scene '" + impl_->name + "' already has an arena");
  Part part = scene_detail::arena_part(arena);
  impl_->add_part(std::move(part), "arena", impl_->sec("worldbody"), std::nullopt);
  impl_->arena = true;
}

void Scene::add_robot(const RobotSpec& spec) {
  validate(spec);
  if (impl_->robots.count(spec.name))
    throw Error("robot name '" + spec.name + "' is used twice in scene '" + impl_->name + "'");
  const fs::path file = resolve_model(spec.model, Robot::models_dir(), "robot");
  Part part = scene_detail::load_part(file, "robot '" + spec.name + "' (" + file.string() + ")");
  if (!spec.keep_arena) scene_detail::strip_arena(part.root);
  XmlNode mount = element(
      "body",
      {{"name", spec.name}, {"pos", numbers_text(spec.pos)}, {"quat", numbers_text(spec.quat)}});
  impl_->add_part(std::move(part), spec.name, impl_->sec("worldbody"), std::move(mount));
  impl_->robots.insert(spec.name);
}

void Scene::attach_gripper(const GripperSpec& spec) {
  validate(spec);
  if (!impl_->robots.count(spec.robot)) {
    const std::vector<std::string> robots(impl_->robots.begin(), impl_->robots.end());
    throw Error("gripper '" + spec.name + "': no robot named '" + spec.robot + "' in scene '" +
                impl_->name + "'" + (robots.empty() ? "" : "; robots: " + list(robots)));
  }
  const std::string frame = spec.robot + "/" + spec.frame;
  XmlNode* body = find_in(impl_->root, "body", frame);
  XmlNode* site = body ? nullptr : find_in(impl_->root, "site", frame);
  if (!body && !site) {
    // frames of this robot only, unprefixed
    std::vector<std::string> frames;
    for (const auto& [key, owner] : impl_->owners) {
      if ((key.first == "site" || key.first == "body") &&
          key.second.rfind(spec.robot + "/", 0) == 0)
        frames.push_back(key.second.substr(spec.robot.size() + 1));
    }
    std::string message = "gripper '" + spec.name + "': unknown attachment frame '" + spec.frame +
                          "' on robot '" + spec.robot + "' (expected one of its sites or bodies)";
    const auto close = closest_names(spec.frame, frames, 3);
    if (!close.empty()) message += "; closest: " + list(close);
    throw Error(message);
  }
  const fs::path dir = Robot::models_dir() / "grippers";
  const fs::path file = resolve_model(spec.model, dir, "gripper");
  const std::string prefix = spec.robot + "/" + spec.name;
  Part part = scene_detail::load_part(file, "gripper '" + prefix + "' (" + file.string() + ")");
  scene_detail::strip_arena(part.root);
  XmlNode mount = element("body", {{"name", prefix}});
  XmlNode* parent = body;
  if (site) {
    // the mount takes the site's place in the site's body
    parent = parent_of(impl_->root, site);
    for (const char* key : {"pos", "quat", "xyaxes", "zaxis"})
      if (const std::string* v = site->find(key)) mount.set(key, *v);
  }
  impl_->add_part(std::move(part), prefix, *parent, std::move(mount));
}

void Scene::add_object(const ObjectSpec& spec) {
  Part part = scene_detail::object_part(spec, true);
  XmlNode mount = element(
      "body",
      {{"name", spec.name}, {"pos", numbers_text(spec.pos)}, {"quat", numbers_text(spec.quat)}});
  impl_->add_part(std::move(part), spec.name, impl_->sec("worldbody"), std::move(mount));
}

void Scene::add_fixture(const ObjectSpec& spec) {
  Part part = scene_detail::object_part(spec, false);
  part.source = "fixture '" + spec.name + "'";
  XmlNode mount = element(
      "body",
      {{"name", spec.name}, {"pos", numbers_text(spec.pos)}, {"quat", numbers_text(spec.quat)}});
  impl_->add_part(std::move(part), spec.name, impl_->sec("worldbody"), std::move(mount));
}

void Scene::add_fixture(const CompoundFixtureSpec& spec) {
  Part part = scene_detail::compound_part(spec);
  XmlNode mount = element(
      "body",
      {{"name", spec.name}, {"pos", numbers_text(spec.pos)}, {"quat", numbers_text(spec.quat)}});
  impl_->add_part(std::move(part), spec.name, impl_->sec("worldbody"), std::move(mount));
}

void Scene::add_camera(const SceneCameraSpec& spec) {
  validate(spec);
  const std::string source = "camera '" + spec.name + "'";
  impl_->check_single("camera", spec.name, source);
  XmlNode camera = element("camera", {{"name", spec.name}, {"pos", numbers_text(spec.pos)}});
  const bool axes =
      std::any_of(spec.xyaxes.begin(), spec.xyaxes.end(), [](double v) { return v != 0.0; });
  if (axes) {
    camera.set("xyaxes", numbers_text(spec.xyaxes));
  } else {
    camera.set("quat", numbers_text(spec.quat));
  }
  camera.set("fovy", numbers_text(std::span<const double>(&spec.fovy, 1)));
  if (!spec.target.empty()) {
    impl_->require("body", spec.target, source + " target");
    camera.set("mode", "targetbody");
    camera.set("target", spec.target);
  }
  XmlNode& parent = impl_->body_or_world(spec.body, source + " parent");
  parent.children.push_back(std::move(camera));
  impl_->claim({{"camera", spec.name}}, source);
}

void Scene::add_site(const SiteSpec& spec) {
  validate(spec);
  const std::string source = "site '" + spec.name + "'";
  impl_->check_single("site", spec.name, source);
  XmlNode& parent = impl_->body_or_world(spec.body, source + " parent");
  parent.children.push_back(
      element("site", {{"name", spec.name},
                       {"pos", numbers_text(spec.pos)},
                       {"quat", numbers_text(spec.quat)},
                       {"size", numbers_text(std::span<const double>(&spec.size, 1))},
                       {"rgba", numbers_text(spec.rgba)}}));
  impl_->claim({{"site", spec.name}}, source);
}

void Scene::add_sensor(const SensorSpec& spec) {
  const std::string source = std::string(to_string(spec.type)) + " sensor '" + spec.name + "'";
  if (spec.name.empty()) throw Error("a sensor needs a non-empty name");
  if (spec.target.empty()) throw Error(source + " needs a target");
  impl_->check_single("sensor", spec.name, source);
  XmlNode sensor = element(to_string(spec.type), {{"name", spec.name}});
  switch (spec.type) {
    case SensorType::jointpos:
      impl_->require("joint", spec.target, source);
      sensor.set("joint", spec.target);
      break;
    case SensorType::touch:
    case SensorType::force:
    case SensorType::torque:
      impl_->require("site", spec.target, source);
      sensor.set("site", spec.target);
      break;
    case SensorType::framepos:
    case SensorType::framequat: {
      // a site, a body's own frame (xbody), a geom or a camera
      const std::pair<const char*, const char*> kinds[] = {
          {"site", "site"}, {"body", "xbody"}, {"geom", "geom"}, {"camera", "camera"}};
      const char* objtype = nullptr;
      for (const auto& [kind, type] : kinds) {
        if (find_in(impl_->root, kind, spec.target)) {
          objtype = type;
          break;
        }
      }
      if (!objtype) impl_->require("site", spec.target, source + " (a site, body, geom or camera)");
      sensor.set("objtype", objtype);
      sensor.set("objname", spec.target);
      break;
    }
  }
  impl_->sec("sensor").children.push_back(std::move(sensor));
  impl_->claim({{"sensor", spec.name}}, source);
}

void Scene::add_weld(const WeldSpec& spec) {
  validate(spec);
  const std::string source = "weld '" + spec.name + "'";
  impl_->check_single("equality", spec.name, source);
  impl_->require("body", spec.body1, source + " body1");
  impl_->require("body", spec.body2, source + " body2");
  impl_->sec("equality")
      .children.push_back(element("weld", {{"name", spec.name},
                                           {"body1", spec.body1},
                                           {"body2", spec.body2},
                                           {"active", spec.active ? "true" : "false"},
                                           {"solref", numbers_text(spec.solref)}}));
  impl_->claim({{"equality", spec.name}}, source);
}

bool Scene::has(std::string_view kind, std::string_view element_name) const {
  return find_in(impl_->root, kind, element_name) != nullptr;
}

std::vector<std::string> Scene::names(std::string_view kind) const {
  std::vector<std::string> out;
  for (const auto& [key, owner] : impl_->owners)
    if (key.first == kind) out.push_back(key.second);
  return out;
}

std::optional<std::string> Scene::attribute(std::string_view kind, std::string_view element_name,
                                            std::string_view attr) const {
  const XmlNode& e = impl_->require(kind, element_name, "attribute '" + std::string(attr) + "'");
  const std::string* v = e.find(attr);
  return v ? std::optional(*v) : std::nullopt;
}

void Scene::set_attribute(std::string_view kind, std::string_view element_name,
                          std::string_view attr, std::string_view value) {
  const std::string what = std::string(kind) + " '" + std::string(element_name) + "'";
  if (attr == "name" || (kind == "default" && attr == "class"))
    throw Error(what + ": renaming is not supported (names are checked when parts are added)");
  if (attr.empty()) throw Error(what + ": an attribute name is needed");
  XmlNode& e = impl_->require(kind, element_name, "set " + std::string(attr));
  e.set(attr, std::string(value));
}

void Scene::set_attribute(std::string_view kind, std::string_view element_name,
                          std::string_view attr, std::span<const double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) {
      throw Error(std::string(kind) + " '" + std::string(element_name) + "': " + std::string(attr) +
                  " must be finite numbers");
    }
  }
  if (values.empty())
    throw Error(std::string(kind) + " '" + std::string(element_name) + "': " + std::string(attr) +
                " needs at least one value");
  set_attribute(kind, element_name, attr, std::string_view(numbers_text(values)));
}

void Scene::set_option(std::string_view attr, std::string_view value) {
  if (attr.empty()) throw Error("scene '" + impl_->name + "': set_option needs an attribute name");
  impl_->sec("option").set(std::string(attr), std::string(value));
}

std::string Scene::xml() const { return mjcf_detail::write_document(impl_->root); }

Robot Scene::compile() const {
  const auto load = [&](const XmlNode& root) {
    try {
      return Robot::from_string(mjcf_detail::write_document(root));
    } catch (const Error& e) {
      throw Error("scene '" + impl_->name + "' does not compile: " + e.what());
    }
  };
  if (impl_->keys.empty()) return load(impl_->root);
  // keys need the scene's qpos layout: compile once without them
  const Robot plain = load(impl_->root);
  const mjModel& m = plain.model();
  XmlNode root = impl_->root;
  XmlNode keyframe = element("keyframe");
  std::vector<std::string> done;
  for (std::size_t i = 0; i < impl_->keys.size(); ++i) {
    const std::string& local = impl_->local_key_names[i];
    if (std::find(done.begin(), done.end(), local) != done.end()) continue;
    done.push_back(local);
    std::vector<double> qpos(m.qpos0, m.qpos0 + m.nq);
    std::vector<double> ctrl(static_cast<std::size_t>(m.nu), 0.0);
    for (std::size_t j = i; j < impl_->keys.size(); ++j) {
      if (impl_->local_key_names[j] != local) continue;
      for (const auto& [joint, values] : impl_->keys[j].qpos) {
        const int id = try_find_object(m, mjOBJ_JOINT, joint);
        if (id < 0) continue;
        const int adr = m.jnt_qposadr[id];
        const int size = id + 1 < m.njnt ? m.jnt_qposadr[id + 1] - adr : m.nq - adr;
        if (static_cast<int>(values.size()) == size)
          std::copy(values.begin(), values.end(), qpos.begin() + adr);
      }
      for (const auto& [actuator, value] : impl_->keys[j].ctrl) {
        const int id = try_find_object(m, mjOBJ_ACTUATOR, actuator);
        if (id >= 0) ctrl[static_cast<std::size_t>(id)] = value;
      }
    }
    XmlNode key = element("key", {{"name", local}, {"qpos", numbers_text(qpos)}});
    if (m.nu > 0) key.set("ctrl", numbers_text(ctrl));
    keyframe.children.push_back(std::move(key));
  }
  root.children.push_back(std::move(keyframe));
  return load(root);
}

}  // namespace mjarm
