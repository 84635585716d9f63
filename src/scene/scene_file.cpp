#include "mjarm/scene/scene_file.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <initializer_list>
#include <map>

#include "frame_check.hpp"
#include "mjarm/error.hpp"
#include "mjarm/model/model_size.hpp"
#include "mjarm/model/names.hpp"
#include "mjarm/model/user_file.hpp"
#include "yaml_documents.hpp"

namespace mjarm {

namespace fs = std::filesystem;

namespace {

/// One YAML mapping whose keys were checked against the known ones.
class Fields {
 public:
  Fields(const YAML::Node& node, std::string what, std::vector<std::string> known,
         const std::string& source)
      : node_(node), what_(std::move(what)), source_(source) {
    if (!node.IsMap()) fail(node, what_ + " must be a mapping of keys to values");
    for (const auto& entry : node) {
      const std::string key = entry.first.Scalar();
      if (std::find(known.begin(), known.end(), key) == known.end())
        fail(entry.first, unknown_name_message("key", key, known, what_));
      if (!values_.emplace(key, entry.second).second)
        fail(entry.first, "key '" + key + "' appears twice in " + what_);
    }
  }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& message) const {
    const YAML::Mark mark = n.Mark();
    throw Error(source_ + (mark.is_null() ? std::string() : ":" + std::to_string(mark.line + 1)) +
                ": " + message);
  }

  bool has(const std::string& key) const { return values_.count(key) > 0; }
  const YAML::Node& at(const std::string& key) const {
    const auto it = values_.find(key);
    if (it == values_.end()) fail(node_, what_ + " needs the key '" + key + "'");
    return it->second;
  }
  int line() const { return node_.Mark().is_null() ? 0 : node_.Mark().line + 1; }

  std::string text(const std::string& key) const {
    const YAML::Node& n = at(key);
    if (!n.IsScalar()) fail(n, "key '" + key + "' in " + what_ + " expects a string");
    return n.Scalar();
  }
  double number(const std::string& key) const { return number_of(at(key), key); }
  bool flag(const std::string& key) const {
    const YAML::Node& n = at(key);
    try {
      if (n.IsScalar()) return n.as<bool>();
    } catch (const YAML::Exception&) {
    }
    fail(n, "key '" + key + "' in " + what_ + " expects true or false, got '" + n.Scalar() + "'");
  }
  std::vector<double> numbers(const std::string& key) const {
    const YAML::Node& n = at(key);
    if (n.IsScalar()) return {number_of(n, key)};
    if (!n.IsSequence()) fail(n, "key '" + key + "' in " + what_ + " expects a list of numbers");
    std::vector<double> out;
    for (const auto& v : n) out.push_back(number_of(v, key));
    return out;
  }
  template <std::size_t N>
  void read(const std::string& key, std::array<double, N>& out) const {
    if (!has(key)) return;
    const auto v = numbers(key);
    if (v.size() != N) {
      fail(at(key), "key '" + key + "' in " + what_ + " expects " + std::to_string(N) +
                        " numbers, got " + std::to_string(v.size()));
    }
    std::copy(v.begin(), v.end(), out.begin());
  }
  void read(const std::string& key, double& out) const {
    if (has(key)) out = number(key);
  }
  void read(const std::string& key, std::string& out) const {
    if (has(key)) out = text(key);
  }
  void read(const std::string& key, bool& out) const {
    if (has(key)) out = flag(key);
  }
  void read(const std::string& key, std::vector<double>& out) const {
    if (has(key)) out = numbers(key);
  }
  void read(const std::string& key, ObjectShape& out) const { read_enum(key, out, &object_shape); }
  void read(const std::string& key, SensorType& out) const { read_enum(key, out, &sensor_type); }

  /// Runs @p add, prefixing any error with this entry's place.
  template <class Fn>
  void apply(Fn&& add) const {
    try {
      add();
    } catch (const Error& e) {
      throw Error(source_ + ":" + std::to_string(line()) + ": " + what_ + ": " + e.what());
    }
  }

 private:
  double number_of(const YAML::Node& n, const std::string& key) const {
    if (n.IsScalar()) {
      try {
        return n.as<double>();
      } catch (const YAML::Exception&) {
      }
    }
    fail(n, "key '" + key + "' in " + what_ + " expects a number" +
                (n.IsScalar() ? ", got '" + n.Scalar() + "'" : std::string()));
  }

  // "s.yaml:2: unknown object shape 'cub'; closest: box; …"
  template <class E>
  void read_enum(const std::string& key, E& out, E (*parse)(std::string_view)) const {
    if (!has(key)) return;
    try {
      out = parse(text(key));
    } catch (const Error& e) {
      fail(at(key), e.what());
    }
  }

  YAML::Node node_;
  std::string what_;
  const std::string& source_;
  std::map<std::string, YAML::Node> values_;
};

/// The keys of a part written as spec @p S: the names its fields declare, but @p left_out, then
/// @p extra.
template <Declared S>
std::vector<std::string> keys_of(std::initializer_list<std::string_view> left_out,
                                 std::initializer_list<std::string_view> extra = {}) {
  std::vector<std::string> keys;
  for_each_field<S>([&](const auto& field) {
    if (std::find(left_out.begin(), left_out.end(), field.name) == left_out.end())
      keys.emplace_back(field.name);
  });
  keys.insert(keys.end(), extra.begin(), extra.end());
  return keys;
}

/// Reads into @p spec every declared field whose key @p f holds, after checking that it holds
/// the @p required ones.
template <Declared S>
void read_declared(const Fields& f, S& spec, std::initializer_list<const char*> required) {
  for (const char* key : required) f.at(key);
  for_each_field<S>(
      [&](const auto& field) { f.read(std::string(field.name), spec.*(field.member)); });
}

// the entries of a top-level list
std::vector<YAML::Node> entries(const Fields& top, const std::string& key) {
  if (!top.has(key)) return {};
  const YAML::Node& n = top.at(key);
  if (!n.IsSequence()) top.fail(n, "key '" + key + "' expects a list");
  return {n.begin(), n.end()};
}

std::string entry_name(const YAML::Node& n, const std::string& kind, std::size_t index) {
  if (n.IsMap() && n["name"] && n["name"].IsScalar()) return kind + " '" + n["name"].Scalar() + "'";
  return kind + " #" + std::to_string(index + 1);
}

std::string resolve(const std::string& path, const fs::path& base_dir, bool maybe_bundled) {
  const fs::path p(path);
  if (maybe_bundled && !p.has_extension() && !p.has_parent_path()) return path;
  return p.is_absolute() ? path : (base_dir / p).lexically_normal().string();
}

ObjectSpec read_object(const Fields& f, const fs::path& base_dir) {
  ObjectSpec spec;
  read_declared(f, spec, {"name"});
  if (!f.has("size") && spec.shape == ObjectShape::mesh) spec.size.clear();
  if (f.has("mesh")) spec.mesh_file = resolve(f.text("mesh"), base_dir, false);
  return spec;
}

void read_arena(Scene& scene, const Fields& top, const std::string& source) {
  if (!top.has("arena")) return;
  const YAML::Node& node = top.at("arena");
  ArenaSpec arena;
  if (node.IsNull()) {
    scene.add_arena(arena);
    return;
  }
  const Fields f(node, "arena", {"floor", "table"}, source);
  f.read("floor", arena.floor_half_size);
  if (f.has("table")) {
    const YAML::Node& t = f.at("table");
    if (t.IsScalar()) {
      arena.table = f.flag("table");
    } else {
      arena.table = true;
      const Fields tf(t, "arena table", {"center", "size", "height", "friction"}, source);
      tf.read("center", arena.table_center);
      tf.read("size", arena.table_half_size);
      tf.read("height", arena.table_height);
      tf.read("friction", arena.table_friction);
    }
  }
  f.apply([&] { scene.add_arena(arena); });
}

}  // namespace

bool is_scene_file(const fs::path& path) {
  return has_extension(path, ".yaml") || has_extension(path, ".yml") ||
         has_extension(path, ".json");
}

Scene parse_scene(std::string_view text, const fs::path& base_dir, const std::string& source) {
  std::vector<YAML::Node> documents;
  try {
    // every document: a second one would otherwise be dropped without a word
    for (YAML::Node& d : load_yaml_documents(std::string(text), source))
      if (!d.IsNull()) documents.push_back(std::move(d));
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own message for this is "bad file"
    throw Error(source + ":" + std::to_string(e.mark.line + 1) + ": nested more than " +
                std::to_string(e.depth() - 2) +
                " levels deep, the limit of the YAML parser (yaml-cpp); a scene needs a few");
  } catch (const YAML::ParserException& e) {
    throw Error(source + ":" + std::to_string(e.mark.line + 1) +
                ": not valid YAML or JSON: " + e.msg);
  }
  const auto line_of = [](const YAML::Node& n) {
    return n.Mark().is_null() ? std::string("?") : std::to_string(n.Mark().line + 1);
  };
  if (documents.size() > 1)
    throw Error(
        source + ":" + line_of(documents[1]) +
        ": a second document starts here (the first at line " + line_of(documents[0]) +
        "); a scene file holds one scene: remove the second or put it in a file of its own");
  const YAML::Node doc = documents.empty() ? YAML::Node() : documents.front();
  if (!doc.IsMap())
    throw Error(source + ": a scene file must be a mapping (name, arena, robots, ...)");
  const Fields top(doc, "the scene",
                   {"name", "arena", "robots", "objects", "fixtures", "cameras", "sites", "sensors",
                    "welds", "edits"},
                   source);
  std::string name = source.empty() || source.front() == '<' ? std::string("scene")
                                                             : fs::path(source).stem().string();
  top.read("name", name);
  // the size bound before any part is added (each robot's own file is counted when it loads)
  ModelSizeCount count;
  for (const char* key : {"robots", "objects", "fixtures", "cameras", "sites", "sensors", "welds",
                          "edits"})
    if (top.has(key) && top.at(key).IsSequence()) count.add(key, top.at(key).size());
  count.check("scene file '" + source + "'");
  Scene scene(name);
  read_arena(scene, top, source);

  const auto robots = entries(top, "robots");
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const Fields f(robots[i], entry_name(robots[i], "robot", i),
                   keys_of<RobotSpec>({}, {"gripper"}), source);
    RobotSpec spec;
    read_declared(f, spec, {"name", "model"});
    spec.model = resolve(spec.model, base_dir, true);
    f.apply([&] { scene.add_robot(spec); });
    if (!f.has("gripper")) continue;
    const Fields g(f.at("gripper"), "gripper of robot '" + spec.name + "'",
                   keys_of<GripperSpec>({"robot"}), source);
    GripperSpec gripper;
    read_declared(g, gripper, {"model", "frame"});
    gripper.robot = spec.name;
    gripper.model = resolve(gripper.model, base_dir, true);
    g.apply([&] { scene.attach_gripper(gripper); });
  }
  // a file names a mesh by its path ("mesh"); vertices are given through the API only
  const std::vector<std::string> object_keys =
      keys_of<ObjectSpec>({"mesh_file", "mesh_vertices"}, {"mesh"});
  for (const char* kind : {"objects", "fixtures"}) {
    const auto list = entries(top, kind);
    const bool free = std::string(kind) == "objects";
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Fields f(list[i], entry_name(list[i], free ? "object" : "fixture", i), object_keys,
                     source);
      const ObjectSpec spec = read_object(f, base_dir);
      f.apply([&] { free ? scene.add_object(spec) : scene.add_fixture(spec); });
    }
  }
  const auto sites = entries(top, "sites");
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Fields f(sites[i], entry_name(sites[i], "site", i), keys_of<SiteSpec>({}), source);
    SiteSpec spec;
    read_declared(f, spec, {"name"});
    f.apply([&] { scene.add_site(spec); });
  }
  const auto cameras = entries(top, "cameras");
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Fields f(cameras[i], entry_name(cameras[i], "camera", i), keys_of<SceneCameraSpec>({}),
                   source);
    SceneCameraSpec spec;
    read_declared(f, spec, {"name"});
    if (f.has("xyaxes")) {
      if (f.has("quat"))
        f.fail(f.at("quat"), "camera '" + spec.name + "' has both 'xyaxes' and 'quat': give one");
      // given, all zero is degenerate (the API reads all zero as "use quat")
      try {
        scene_detail::check_orientation("xyaxes", spec.xyaxes, "camera '" + spec.name + "'");
      } catch (const Error& e) {
        f.fail(f.at("xyaxes"), e.what());
      }
    }
    f.apply([&] { scene.add_camera(spec); });
  }
  const auto sensors = entries(top, "sensors");
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const Fields f(sensors[i], entry_name(sensors[i], "sensor", i), keys_of<SensorSpec>({}),
                   source);
    SensorSpec spec;
    read_declared(f, spec, {"name", "type", "target"});
    f.apply([&] { scene.add_sensor(spec); });
  }
  const auto welds = entries(top, "welds");
  for (std::size_t i = 0; i < welds.size(); ++i) {
    const Fields f(welds[i], entry_name(welds[i], "weld", i), keys_of<WeldSpec>({}), source);
    WeldSpec spec;
    read_declared(f, spec, {"name", "body1", "body2"});
    f.apply([&] { scene.add_weld(spec); });
  }
  const auto edits = entries(top, "edits");
  for (std::size_t i = 0; i < edits.size(); ++i) {
    const Fields f(edits[i], "edit #" + std::to_string(i + 1), {"element", "name", "set"}, source);
    const std::string kind = f.text("element");
    const std::string element_name = f.text("name");
    const YAML::Node& set = f.at("set");
    if (!set.IsMap()) f.fail(set, "key 'set' expects a mapping of attributes to values");
    std::vector<std::string> seen;
    std::string orientation;  // MJCF gives an element one orientation
    for (const auto& entry : set) {
      const std::string attr = entry.first.Scalar();
      if (std::find(seen.begin(), seen.end(), attr) != seen.end())
        f.fail(entry.first,
               "attribute '" + attr + "' appears twice in edit #" + std::to_string(i + 1));
      seen.push_back(attr);
      if (attr == "quat" || attr == "axisangle" || attr == "xyaxes" || attr == "zaxis" ||
          attr == "euler") {
        if (!orientation.empty())
          f.fail(entry.first, "edit #" + std::to_string(i + 1) + " gives " + kind + " '" +
                                  element_name + "' two orientations, '" + orientation + "' and '" +
                                  attr + "': give one");
        orientation = attr;
      }
      if (entry.second.IsSequence()) {
        std::vector<double> values;
        for (const auto& v : entry.second) {
          try {
            values.push_back(v.as<double>());
          } catch (const YAML::Exception&) {
            f.fail(v, "attribute '" + attr + "' expects numbers, got '" + v.Scalar() + "'");
          }
        }
        f.apply([&] { scene.set_attribute(kind, element_name, attr, values); });
      } else if (entry.second.IsScalar()) {
        f.apply([&] { scene.set_attribute(kind, element_name, attr, entry.second.Scalar()); });
      } else {
        f.fail(entry.second, "attribute '" + attr + "' expects a value or a list of numbers");
      }
    }
  }
  return scene;
}

Scene load_scene_file(const fs::path& path) {
  // the one checked reader of user files: regular files only, bounded, never blocking
  const std::string text = read_user_file(path, "scene file");
  return parse_scene(text, fs::absolute(path).parent_path(), path.string());
}

}  // namespace mjarm
