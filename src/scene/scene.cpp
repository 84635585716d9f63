#include "mjarm/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>

#include "mjarm/error.hpp"
#include "mjarm/model/mjcf_spec.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "scene_elements.hpp"
#include "scene_keyframes.hpp"
#include "scene_parts.hpp"
#include "spec_attributes.hpp"

namespace mjarm {

namespace fs = std::filesystem;
using scene_detail::NameKey;
using scene_detail::PartKeys;

namespace {

// kinds of named elements a part brings (default classes are prefixed by mjs_attach too, but a
// spec does not list them; MuJoCo refuses a clash among them when attaching)
constexpr std::pair<std::string_view, mjtObj> kNamedKinds[] = {
    {"body", mjOBJ_BODY},       {"frame", mjOBJ_FRAME},       {"joint", mjOBJ_JOINT},
    {"geom", mjOBJ_GEOM},       {"site", mjOBJ_SITE},         {"camera", mjOBJ_CAMERA},
    {"light", mjOBJ_LIGHT},     {"actuator", mjOBJ_ACTUATOR}, {"sensor", mjOBJ_SENSOR},
    {"tendon", mjOBJ_TENDON},   {"equality", mjOBJ_EQUALITY}, {"pair", mjOBJ_PAIR},
    {"exclude", mjOBJ_EXCLUDE}, {"mesh", mjOBJ_MESH},         {"hfield", mjOBJ_HFIELD},
    {"skin", mjOBJ_SKIN},       {"texture", mjOBJ_TEXTURE},   {"material", mjOBJ_MATERIAL},
    {"numeric", mjOBJ_NUMERIC}, {"text", mjOBJ_TEXT},         {"tuple", mjOBJ_TUPLE},
    {"key", mjOBJ_KEY}};

// element types that take a default class
constexpr mjtObj kClassedTypes[] = {mjOBJ_JOINT,    mjOBJ_GEOM,   mjOBJ_SITE,     mjOBJ_CAMERA,
                                    mjOBJ_LIGHT,    mjOBJ_MESH,   mjOBJ_MATERIAL, mjOBJ_PAIR,
                                    mjOBJ_EQUALITY, mjOBJ_TENDON, mjOBJ_ACTUATOR};

/// The object type of a kind of named element ("body", ..., "key", "default"), or nullopt.
std::optional<mjtObj> object_type(std::string_view kind) {
  if (kind == "default") return mjOBJ_DEFAULT;
  for (const auto& [name, type] : kNamedKinds)
    if (name == kind) return type;
  return std::nullopt;
}

std::string name_of(mjsElement* e) {
  const char* n = mjs_getString(mjs_getName(e));
  return n == nullptr ? std::string() : std::string(n);
}

/// Names of the elements of @p type in @p spec, in the spec's order.
std::vector<std::string> element_names(const mjSpec& spec, mjtObj type) {
  std::vector<std::string> names;
  for (mjsElement* e = mjs_firstElement(&spec, type); e != nullptr; e = mjs_nextElement(&spec, e)) {
    std::string n = name_of(e);
    if (!n.empty()) names.push_back(std::move(n));
  }
  return names;
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
    if (entry.is_regular_file() && has_extension(entry.path(), ".xml"))
      names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

// a bundled name in dir, or a file path
fs::path resolve_model(const std::string& model, const fs::path& dir, const char* what) {
  if (looks_like_path(model)) return model;
  const fs::path file = dir / (model + ".xml");
  std::error_code ec;
  if (fs::is_regular_file(file, ec)) return file;
  // the extension in another case
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (std::error_code type_ec; entry.path().stem() == model &&
                                 has_extension(entry.path(), ".xml") &&
                                 entry.is_regular_file(type_ec))
      return entry.path();
  const auto names = xml_stems(dir);
  std::string message = "unknown " + std::string(what) + " '" + model + "'";
  const auto close = closest_names(model, names, 3);
  if (!close.empty()) message += "; closest: " + list(close);
  throw Error(message + "; bundled " + what + "s in " + dir.string() + ": " + list(names));
}

}  // namespace

struct Scene::Impl {
  std::string name;
  SpecPtr spec;
  std::map<NameKey, std::string> owners;  // every name a part brought -> that part
  std::set<std::string> robots;
  bool arena = false;
  std::vector<PartKeys> keyed;       // parts with keyframes, in the order they came
  std::vector<std::string> options;  // <option> attributes the scene set itself
  std::vector<std::string> warnings;

  Impl() = default;
  Impl(const Impl& other)
      : name(other.name),
        spec(mj_copySpec(other.spec.get())),
        owners(other.owners),
        robots(other.robots),
        arena(other.arena),
        keyed(other.keyed),
        options(other.options),
        warnings(other.warnings) {
    if (!spec) throw Error("scene '" + name + "': MuJoCo could not copy the scene's spec");
  }

  mjsBody* world() const { return mjs_findBody(spec.get(), "world"); }

  std::vector<std::string> names_of(std::string_view kind) const {
    const auto type = object_type(kind);
    if (!type) return {};
    std::vector<std::string> out;
    if (*type == mjOBJ_DEFAULT) {
      // the classes the elements were made with
      std::set<std::string> classes;
      for (mjtObj t : kClassedTypes) {
        for (mjsElement* e = mjs_firstElement(spec.get(), t); e != nullptr;
             e = mjs_nextElement(spec.get(), e))
          if (mjsDefault* d = mjs_getDefault(e)) classes.insert(name_of(d->element));
      }
      out.assign(classes.begin(), classes.end());
    } else {
      out = element_names(*spec, *type);
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  bool exists(std::string_view kind, const std::string& element_name) const {
    const auto type = object_type(kind);
    if (!type) return false;
    if (*type == mjOBJ_DEFAULT) return mjs_findDefault(spec.get(), element_name.c_str()) != nullptr;
    return mjs_findElement(spec.get(), *type, element_name.c_str()) != nullptr;
  }

  /// The element, or an Error naming the closest existing names of that kind.
  mjsElement& require(std::string_view kind, std::string_view element_name,
                      const std::string& why) const {
    const auto type = object_type(kind);
    if (!type || *type == mjOBJ_DEFAULT) {
      std::string kinds;
      for (const auto& [k, t] : kNamedKinds) kinds += (kinds.empty() ? "" : ", ") + std::string(k);
      throw Error(why + ": elements of kind '" + std::string(kind) +
                  "' cannot be found by name; kinds: " + kinds);
    }
    const std::string n(element_name);
    if (mjsElement* e = mjs_findElement(spec.get(), *type, n.c_str())) return *e;
    std::string message =
        why + ": no " + std::string(kind) + " named '" + n + "' in scene '" + name + "'";
    const auto close = closest_names(element_name, names_of(kind), 3);
    if (!close.empty()) message += "; closest: " + list(close);
    throw Error(message);
  }

  mjsBody* body_or_world(const std::string& body, const std::string& why) const {
    if (body.empty()) return world();
    return mjs_asBody(&require("body", body, why));
  }

  /// Refuses names the scene has already or @p names repeats.
  void check_free(const std::vector<NameKey>& names, const std::string& source) const {
    std::set<NameKey> seen;
    for (const auto& key : names) {
      if (exists(key.first, key.second)) {
        const auto it = owners.find(key);
        throw Error("name clash in scene '" + name + "': " + key.first + " '" + key.second +
                    "' of " + source + " is already defined by " +
                    (it == owners.end() ? std::string("the scene") : it->second));
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

  /// Attaches the MJCF part @p part (names prefixed with @p prefix) in a new fixed body
  /// @p mount_name in @p parent at (pos, quat) — in @p frame of the parent when given. Checks
  /// every name first; leaves the scene as it was when MuJoCo refuses the part.
  void attach(SpecPtr part, const std::string& prefix, mjsBody* parent,
              const std::string& mount_name, const double pos[3], const double quat[4],
              const std::string& source, mjsFrame* frame = nullptr) {
    std::vector<NameKey> names{{"body", mount_name}};
    PartKeys keys{prefix, {}, {}, {}};
    for (const auto& [kind, type] : kNamedKinds) {
      for (std::string& n : element_names(*part, type)) {
        if (type == mjOBJ_BODY && n == "world") continue;
        if (type == mjOBJ_KEY) keys.keys.push_back(n);
        if (type == mjOBJ_JOINT) keys.joints.push_back(prefix + n);
        if (type == mjOBJ_ACTUATOR) keys.actuators.push_back(prefix + n);
        names.emplace_back(kind, prefix + n);
      }
    }
    check_free(names, source);
    // the scene's own <option> settings win over the part's
    for (const std::string& attribute : options)
      scene_detail::copy_option(spec->option, part->option, attribute);
    mjsBody* mount = mjs_addBody(parent, nullptr);
    mjs_setName(mount->element, mount_name.c_str());
    std::copy(pos, pos + 3, mount->pos);
    std::copy(quat, quat + 4, mount->quat);
    if (frame != nullptr) mjs_setFrame(mount->element, frame);
    const int known_warnings = mjs_numWarnings(spec.get());
    if (mjs_attach(mount->element, part->element, prefix.c_str(), "") == nullptr) {
      const std::string error = mjs_getError(spec.get());
      mjs_delete(spec.get(), mount->element);
      throw Error(source + ": MuJoCo refuses the part: " + error);
    }
    // MuJoCo's word on global settings (option, size, visual) the part disagrees on
    for (int i = known_warnings; i < mjs_numWarnings(spec.get()); ++i)
      warnings.push_back(source + ": " + mjs_getWarning(spec.get(), i));
    claim(names, source);
    if (!keys.keys.empty()) keyed.push_back(std::move(keys));
  }

  /// A copy of the spec compiled into a Robot, the parts' keyframes combined by name.
  std::pair<SpecPtr, Robot> compile_copy() const {
    return scene_detail::compile_combining_keys(*spec, name, warnings, keyed);
  }
};

Scene::Scene(std::string name) : impl_(std::make_unique<Impl>()) {
  impl_->name = std::move(name);
  impl_->spec.reset(mj_makeSpec());
  mjSpec& spec = *impl_->spec;
  mjs_setString(spec.modelname, impl_->name.c_str());
  // what the scene adds itself is in radians with inferred limits; attached parts keep their
  // own compiler settings
  spec.compiler.degree = 0;
  spec.compiler.autolimits = 1;
  // a part's global setting is taken when the scene has none; disagreements follow MuJoCo's
  // merge rules (min timestep, max iterations, an error for integrator, cone, gravity, ...)
  spec.compiler.conflict = mjCONFLICT_MERGE;
  // parts are copied in, so each part's spec is freed once it is attached
  mjs_setDeepCopy(&spec, 1);
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
  validate(arena);
  const auto names = scene_detail::arena_names(arena);
  impl_->check_free(names, "arena");
  scene_detail::add_arena(*impl_->spec, arena);
  impl_->claim(names, "arena");
  impl_->arena = true;
}

void Scene::add_robot(const RobotSpec& spec) {
  validate(spec);
  if (impl_->robots.count(spec.name))
    throw Error("robot name '" + spec.name + "' is used twice in scene '" + impl_->name + "'");
  const fs::path file = resolve_model(spec.model, Robot::models_dir(), "robot");
  const std::string source = "robot '" + spec.name + "' (" + file.string() + ")";
  std::vector<std::string> parse_warnings;
  SpecPtr part = parse_mjcf_file(file, &parse_warnings);
  if (!spec.keep_arena) scene_detail::strip_arena(*part);
  impl_->attach(std::move(part), spec.name + "/", impl_->world(), spec.name, spec.pos.data(),
                spec.quat.data(), source);
  for (const auto& w : parse_warnings) impl_->warnings.push_back(source + ": " + w);
  impl_->robots.insert(spec.name);
}

void Scene::attach_gripper(const GripperSpec& spec) {
  validate(spec);
  if (!impl_->robots.count(spec.robot)) {
    const std::vector<std::string> robots(impl_->robots.begin(), impl_->robots.end());
    throw Error("gripper '" + spec.name + "': no robot named '" + spec.robot + "' in scene '" +
                impl_->name + "'" + (robots.empty() ? "" : "; robots: " + list(robots)));
  }
  mjSpec* scene = impl_->spec.get();
  const std::string frame = spec.robot + "/" + spec.frame;
  mjsBody* body = mjs_findBody(scene, frame.c_str());
  mjsSite* site = body ? nullptr : mjs_asSite(mjs_findElement(scene, mjOBJ_SITE, frame.c_str()));
  if (!body && !site) {
    // frames of this robot only, unprefixed
    std::vector<std::string> frames;
    for (const char* kind : {"site", "body"}) {
      for (const std::string& n : impl_->names_of(kind))
        if (n.rfind(spec.robot + "/", 0) == 0) frames.push_back(n.substr(spec.robot.size() + 1));
    }
    std::string message = "gripper '" + spec.name + "': unknown attachment frame '" + spec.frame +
                          "' on robot '" + spec.robot + "' (expected one of its sites or bodies)";
    const auto close = closest_names(spec.frame, frames, 3);
    if (!close.empty()) message += "; closest: " + list(close);
    throw Error(message);
  }
  const fs::path file = resolve_model(spec.model, Robot::models_dir() / "grippers", "gripper");
  const std::string prefix = spec.robot + "/" + spec.name;
  const std::string source = "gripper '" + prefix + "' (" + file.string() + ")";
  std::vector<std::string> parse_warnings;
  SpecPtr part = parse_mjcf_file(file, &parse_warnings);
  scene_detail::strip_arena(*part);
  double pos[3] = {0.0, 0.0, 0.0};
  double quat[4] = {1.0, 0.0, 0.0, 0.0};
  mjsBody* parent = body;
  if (site) {
    // the mount takes the site's place in the site's body: its pose as the robot's own
    // compiler reads it (angle unit, euler sequence)
    parent = mjs_getParent(site->element);
    std::copy(site->pos, site->pos + 3, pos);
    std::copy(site->quat, site->quat + 4, quat);
    if (site->alt.type != mjORIENTATION_QUAT) {
      const mjsCompiler* compiler = mjs_getCompiler(site->element);
      if (const char* error =
              mjs_resolveOrientation(quat, compiler->degree, compiler->eulerseq, &site->alt))
        throw Error(source + ": the orientation of site '" + frame + "': " + error);
    }
  }
  impl_->attach(std::move(part), prefix + "/", parent, prefix, pos, quat, source,
                site ? mjs_getFrame(site->element) : nullptr);
  for (const auto& w : parse_warnings) impl_->warnings.push_back(source + ": " + w);
}

void Scene::add_object(const ObjectSpec& spec) {
  validate(spec);
  const std::string mesh_file = scene_detail::object_mesh_file(spec);
  const auto names = scene_detail::object_names(spec, true);
  const std::string source = "object '" + spec.name + "'";
  impl_->check_free(names, source);
  scene_detail::add_object(*impl_->spec, spec, true, mesh_file);
  impl_->claim(names, source);
}

void Scene::add_fixture(const ObjectSpec& spec) {
  validate(spec);
  const std::string mesh_file = scene_detail::object_mesh_file(spec);
  const auto names = scene_detail::object_names(spec, false);
  const std::string source = "fixture '" + spec.name + "'";
  impl_->check_free(names, source);
  scene_detail::add_object(*impl_->spec, spec, false, mesh_file);
  impl_->claim(names, source);
}

void Scene::add_fixture(const CompoundFixtureSpec& spec) {
  validate(spec);
  std::vector<std::string> mesh_files;
  for (const ObjectSpec& piece : spec.pieces)
    mesh_files.push_back(scene_detail::object_mesh_file(piece));
  const auto names = scene_detail::compound_names(spec);
  const std::string source = "fixture '" + spec.name + "'";
  impl_->check_free(names, source);
  scene_detail::add_compound(*impl_->spec, spec, mesh_files);
  impl_->claim(names, source);
}

void Scene::add_camera(const SceneCameraSpec& spec) {
  validate(spec);
  const std::string source = "camera '" + spec.name + "'";
  impl_->check_free({{"camera", spec.name}}, source);
  mjsBody* parent = impl_->body_or_world(spec.body, source + " parent");
  if (!spec.target.empty()) impl_->require("body", spec.target, source + " target");
  mjsCamera* camera = mjs_addCamera(parent, nullptr);
  mjs_setName(camera->element, spec.name.c_str());
  std::copy(spec.pos.begin(), spec.pos.end(), camera->pos);
  const bool axes =
      std::any_of(spec.xyaxes.begin(), spec.xyaxes.end(), [](double v) { return v != 0.0; });
  if (axes) {
    camera->alt.type = mjORIENTATION_XYAXES;
    std::copy(spec.xyaxes.begin(), spec.xyaxes.end(), camera->alt.xyaxes);
  } else {
    std::copy(spec.quat.begin(), spec.quat.end(), camera->quat);
  }
  camera->fovy = spec.fovy;
  if (!spec.target.empty()) {
    camera->mode = mjCAMLIGHT_TARGETBODY;
    mjs_setString(camera->targetbody, spec.target.c_str());
  }
  impl_->claim({{"camera", spec.name}}, source);
}

void Scene::add_site(const SiteSpec& spec) {
  validate(spec);
  const std::string source = "site '" + spec.name + "'";
  impl_->check_free({{"site", spec.name}}, source);
  mjsBody* parent = impl_->body_or_world(spec.body, source + " parent");
  mjsSite* site = mjs_addSite(parent, nullptr);
  mjs_setName(site->element, spec.name.c_str());
  std::copy(spec.pos.begin(), spec.pos.end(), site->pos);
  std::copy(spec.quat.begin(), spec.quat.end(), site->quat);
  site->size[0] = spec.size;
  std::copy(spec.rgba.begin(), spec.rgba.end(), site->rgba);
  impl_->claim({{"site", spec.name}}, source);
}

void Scene::add_sensor(const SensorSpec& spec) {
  const std::string source = std::string(to_string(spec.type)) + " sensor '" + spec.name + "'";
  if (spec.name.empty()) throw Error("a sensor needs a non-empty name");
  if (spec.target.empty()) throw Error(source + " needs a target");
  impl_->check_free({{"sensor", spec.name}}, source);
  mjtSensor type = mjSENS_FRAMEPOS;
  mjtObj objtype = mjOBJ_SITE;
  switch (spec.type) {
    case SensorType::jointpos:
      impl_->require("joint", spec.target, source);
      type = mjSENS_JOINTPOS;
      objtype = mjOBJ_JOINT;
      break;
    case SensorType::touch:
    case SensorType::force:
    case SensorType::torque:
      impl_->require("site", spec.target, source);
      type = spec.type == SensorType::touch   ? mjSENS_TOUCH
             : spec.type == SensorType::force ? mjSENS_FORCE
                                              : mjSENS_TORQUE;
      break;
    case SensorType::framepos:
    case SensorType::framequat: {
      // a site, a body's own frame (xbody), a geom or a camera
      type = spec.type == SensorType::framepos ? mjSENS_FRAMEPOS : mjSENS_FRAMEQUAT;
      const std::pair<const char*, mjtObj> kinds[] = {{"site", mjOBJ_SITE},
                                                      {"body", mjOBJ_XBODY},
                                                      {"geom", mjOBJ_GEOM},
                                                      {"camera", mjOBJ_CAMERA}};
      const auto found = std::find_if(std::begin(kinds), std::end(kinds), [&](const auto& k) {
        return impl_->exists(k.first, spec.target);
      });
      if (found == std::end(kinds))
        impl_->require("site", spec.target, source + " (a site, body, geom or camera)");
      objtype = found->second;
      break;
    }
  }
  mjsSensor* sensor = mjs_addSensor(impl_->spec.get());
  mjs_setName(sensor->element, spec.name.c_str());
  sensor->type = type;
  sensor->objtype = objtype;
  mjs_setString(sensor->objname, spec.target.c_str());
  impl_->claim({{"sensor", spec.name}}, source);
}

void Scene::add_weld(const WeldSpec& spec) {
  validate(spec);
  const std::string source = "weld '" + spec.name + "'";
  impl_->check_free({{"equality", spec.name}}, source);
  impl_->require("body", spec.body1, source + " body1");
  impl_->require("body", spec.body2, source + " body2");
  mjsEquality* weld = mjs_addEquality(impl_->spec.get(), nullptr);
  mjs_setName(weld->element, spec.name.c_str());
  weld->type = mjEQ_WELD;
  weld->objtype = mjOBJ_BODY;
  mjs_setString(weld->name1, spec.body1.c_str());
  mjs_setString(weld->name2, spec.body2.c_str());
  // as MJCF's <weld> without anchor or relpose: the relative pose at qpos0 (relpose "0 1 0 0 0
  // 0 0", a zero quaternion, asks the compiler for it)
  std::fill_n(weld->data, 10, 0.0);
  weld->data[4] = 1.0;
  weld->active = spec.active;
  std::copy(spec.solref.begin(), spec.solref.end(), weld->solref);
  impl_->claim({{"equality", spec.name}}, source);
}

void Scene::add(const ElementSpec& element) {
  const std::string what = element.tag + " '" + element.name + "'";
  const auto kind = scene_detail::element_kind(element.tag);
  if (!kind) {
    throw Error("scene '" + impl_->name +
                "': " + unknown_name_message("tag", element.tag, scene_detail::all_tags()));
  }
  if (element.name.empty())
    throw Error("scene '" + impl_->name + "': a " + element.tag + " to add needs a name");
  if (*kind == "default") {
    if (mjs_findDefault(impl_->spec.get(), element.name.c_str()) != nullptr)
      throw Error("name clash in scene '" + impl_->name + "': default class '" + element.name +
                  "' exists already");
  } else {
    impl_->check_free({{std::string(*kind), element.name}}, "an added " + element.tag);
  }
  if (*kind != "actuator" && *kind != "sensor" && *kind != "default" && !element.parent.empty())
    impl_->require("body", element.parent, what + " parent");
  // the class it starts from: its own, or a default's parent class
  const std::string& class_name = *kind == "default" ? element.parent : element.class_name;
  if (!class_name.empty() && mjs_findDefault(impl_->spec.get(), class_name.c_str()) == nullptr) {
    throw Error(what + ": no default class '" + class_name + "' in scene '" + impl_->name +
                "'; classes: " + list(impl_->names_of("default")));
  }
  // made on a copy that replaces the spec once every attribute was taken
  impl_->spec = scene_detail::with_element(*impl_->spec, element, class_name, what);
  if (*kind != "default")
    impl_->claim({{std::string(*kind), element.name}}, "an added " + element.tag);
}

bool Scene::has(std::string_view kind, std::string_view element_name) const {
  return impl_->exists(kind, std::string(element_name));
}

std::vector<std::string> Scene::names(std::string_view kind) const { return impl_->names_of(kind); }

std::optional<std::string> Scene::attribute(std::string_view kind, std::string_view element_name,
                                            std::string_view attr) const {
  mjsElement& e = impl_->require(kind, element_name, "attribute '" + std::string(attr) + "'");
  return scene_detail::read_attribute(e, attr,
                                      std::string(kind) + " '" + std::string(element_name) + "'");
}

void Scene::set_attribute(std::string_view kind, std::string_view element_name,
                          std::string_view attr, std::string_view value) {
  const std::string what = std::string(kind) + " '" + std::string(element_name) + "'";
  if (attr == "name")
    throw Error(what + ": renaming is not supported (names are checked when parts are added)");
  if (attr.empty()) throw Error(what + ": an attribute name is needed");
  mjsElement& e = impl_->require(kind, element_name, "set " + std::string(attr));
  scene_detail::write_attribute(e, attr, value, what);
}

void Scene::set_attribute(std::string_view kind, std::string_view element_name,
                          std::string_view attr, std::span<const double> values) {
  const std::string what = std::string(kind) + " '" + std::string(element_name) + "'";
  for (double v : values)
    if (!std::isfinite(v)) throw Error(what + ": " + std::string(attr) + " must be finite numbers");
  if (values.empty()) throw Error(what + ": " + std::string(attr) + " needs at least one value");
  if (attr == "name")
    throw Error(what + ": renaming is not supported (names are checked when parts are added)");
  mjsElement& e = impl_->require(kind, element_name, "set " + std::string(attr));
  scene_detail::write_attribute(e, attr, values, what);
}

void Scene::set_option(std::string_view attr, std::string_view value) {
  if (attr.empty()) throw Error("scene '" + impl_->name + "': set_option needs an attribute name");
  scene_detail::write_option(impl_->spec->option, attr, value);
  if (std::find(impl_->options.begin(), impl_->options.end(), attr) == impl_->options.end())
    impl_->options.emplace_back(attr);
}

std::string Scene::xml() const {
  const SpecPtr compiled = impl_->compile_copy().first;
  // the spec as written, every number exact (the compiled values are rounded to 6 digits)
  compiled->compiler.savecompiled = 0;
  std::string text(1 << 16, '\0');
  char error[1024] = "";
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int result = mj_saveXMLString(compiled.get(), text.data(), static_cast<int>(text.size()),
                                        error, sizeof(error));
    if (result == 0) {
      text.resize(text.find('\0'));
      return text;
    }
    if (result < 0) break;
    text.assign(static_cast<std::size_t>(result) + 1, '\0');  // the size MuJoCo asked for
  }
  throw Error("scene '" + impl_->name + "': MuJoCo cannot write it as MJCF: " + error);
}

Robot Scene::compile() const { return impl_->compile_copy().second; }

}  // namespace mjarm
