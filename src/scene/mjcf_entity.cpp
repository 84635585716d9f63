#include "mjcf_entity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/model/mjcf_staging.hpp"

namespace mjarm::scene_detail {

namespace fs = std::filesystem;
using mjcf_detail::Context;
using mjcf_detail::Defaults;

namespace {

// attributes whose value names another element (or a default class)
const std::set<std::string, std::less<>> kReferenceAttrs = {
    "class",   "childclass", "joint",   "jointinparent", "joint1",     "joint2",    "tendon",
    "tendon1", "tendon2",    "site",    "sidesite",      "slidersite", "cranksite", "refsite",
    "body",    "body1",      "body2",   "geom",          "geom1",      "geom2",     "actuator",
    "mesh",    "material",   "texture", "hfield",        "objname",    "refname",   "target"};

// elements that accept a class attribute (MuJoCo 2.2.2 schema)
bool takes_class(std::string_view tag, std::string_view parent) {
  if (parent == "asset") return tag == "mesh" || tag == "material";
  if (parent == "worldbody" || parent == "body")
    return tag == "joint" || tag == "geom" || tag == "site" || tag == "camera" || tag == "light";
  if (parent == "contact") return tag == "pair";
  if (parent == "equality" || parent == "actuator") return true;
  if (parent == "tendon") return tag == "spatial" || tag == "fixed";
  return false;
}

int coordinates(std::string_view type) {
  if (type == "free") return 7;
  if (type == "ball") return 4;
  return 1;
}

// calls fn(joint element, class in effect) for every joint and freejoint, in MuJoCo's order
template <class Fn>
void walk_joints(XmlNode& body, const std::string& childclass, Fn&& fn) {
  const std::string* own = body.tag == "body" ? body.find("childclass") : nullptr;
  const std::string cc = own ? *own : childclass;
  for (auto& c : body.children) {
    if (c.tag == "joint" || c.tag == "freejoint") {
      const std::string* cls = c.find("class");
      fn(c, cls ? *cls : (cc.empty() ? std::string("main") : cc));
    }
  }
  for (auto& c : body.children)
    if (c.tag == "body") walk_joints(c, cc, fn);
}

std::string joint_type(const XmlNode& joint, const std::string& cls, const Defaults& defaults) {
  if (joint.tag == "freejoint") return "free";
  if (const std::string* t = joint.find("type")) return *t;
  return defaults.lookup(cls, "joint", "type").value_or("hinge");
}

std::vector<PartKey> take_keys(XmlNode& root) {
  Defaults defaults(root);
  // qpos layout: joints in body order, unnamed ones keep their slot
  std::vector<std::pair<std::string, int>> layout;
  for (auto& c : root.children) {
    if (c.tag != "worldbody") continue;
    walk_joints(c, "", [&](XmlNode& j, const std::string& cls) {
      const std::string* n = j.find("name");
      layout.emplace_back(n ? *n : "", coordinates(joint_type(j, cls, defaults)));
    });
  }
  std::vector<std::string> actuators;
  for (auto& c : root.children) {
    if (c.tag != "actuator") continue;
    for (auto& a : c.children) {
      const std::string* n = a.find("name");
      actuators.push_back(n ? *n : "");
    }
  }
  std::vector<PartKey> keys;
  std::vector<XmlNode> kept;
  for (auto& c : root.children) {
    if (c.tag != "keyframe") {
      kept.push_back(std::move(c));
      continue;
    }
    for (const auto& k : c.children) {
      const std::string* n = k.find("name");
      if (!n) continue;  // an unnamed key cannot be asked for
      PartKey key{*n, {}, {}};
      const auto qpos = mjcf_detail::numbers(k, "qpos");
      std::size_t at = 0;
      for (const auto& [joint, size] : layout) {
        if (at + static_cast<std::size_t>(size) > qpos.size()) break;
        if (!joint.empty())
          key.qpos.emplace_back(joint,
                                std::vector<double>(qpos.begin() + at, qpos.begin() + at + size));
        at += static_cast<std::size_t>(size);
      }
      const auto ctrl = mjcf_detail::numbers(k, "ctrl");
      for (std::size_t i = 0; i < ctrl.size() && i < actuators.size(); ++i)
        if (!actuators[i].empty()) key.ctrl.emplace_back(actuators[i], ctrl[i]);
      keys.push_back(std::move(key));
    }
  }
  root.children = std::move(kept);
  return keys;
}

std::string prefixed(const std::string& prefix, const std::string& name) {
  return prefix + "/" + name;
}

// gives top-level elements that would have used the main default the part's own main class
void assign_main_class(XmlNode& node, const std::string& main_class) {
  for (auto& c : node.children) {
    if (node.tag == "worldbody" && c.tag == "body") {
      if (!c.has("childclass")) c.set("childclass", main_class);
      continue;
    }
    if (takes_class(c.tag, node.tag) && !c.has("class")) c.set("class", main_class);
  }
}

}  // namespace

XmlNode& section(XmlNode& root, std::string_view tag) {
  for (auto& c : root.children)
    if (c.tag == tag) return c;
  XmlNode node;
  node.tag = std::string(tag);
  root.children.push_back(std::move(node));
  return root.children.back();
}

std::string name_kind(std::string_view tag, std::string_view parent) {
  if (parent == "actuator" || parent == "sensor" || parent == "equality" || parent == "tendon")
    return std::string(parent);
  if (parent == "keyframe") return "key";
  if (tag == "freejoint") return "joint";
  if (tag == "default") return "default";
  if (parent == "default") return "";
  static const std::set<std::string, std::less<>> kNamed = {
      "body",     "joint",  "geom", "site", "camera",  "light",   "mesh", "texture",
      "material", "hfield", "skin", "pair", "exclude", "numeric", "text", "tuple"};
  return kNamed.count(tag) ? std::string(tag) : std::string();
}

void normalize_part(XmlNode& root) {
  Context ctx;
  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    if (const std::string* v = c.find("angle")) ctx.degrees = *v != "radian";
    if (const std::string* v = c.find("eulerseq")) ctx.eulerseq = *v;
  }
  // orientations that depend on the angle unit or the euler sequence become quaternions
  mjcf_detail::for_each_element(root, [&](XmlNode& e, XmlNode&) {
    if (!e.has("euler") && !e.has("axisangle")) return;
    const auto q = mjcf_detail::read_orientation(e, ctx);
    mjcf_detail::erase_orientation(e);
    e.set("quat", mjcf_detail::format_numbers(*q));
  });
  if (ctx.degrees) {
    // angles of hinge and ball joints, written on each joint (a default class may serve slide
    // joints too, whose values are lengths)
    const Defaults defaults(root);
    const double unit = std::numbers::pi / 180.0;
    for (auto& c : root.children) {
      if (c.tag != "worldbody") continue;
      walk_joints(c, "", [&](XmlNode& j, const std::string& cls) {
        const std::string type = joint_type(j, cls, defaults);
        if (type != "hinge" && type != "ball") return;
        for (const char* attr : {"range", "ref", "springref"}) {
          const std::string* own = j.find(attr);
          const auto value = own ? std::optional(*own) : defaults.lookup(cls, "joint", attr);
          if (!value) continue;
          auto v = mjcf_detail::parse_numbers(j, attr, *value);
          for (double& x : v) x *= unit;
          j.set(attr, mjcf_detail::format_numbers(v));
        }
      });
    }
  }
  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    c.set("angle", "radian");
    c.erase("eulerseq");
    // asset paths are absolute already
    c.erase("meshdir");
    c.erase("texturedir");
  }
}

Part load_part(const fs::path& file, std::string source) {
  const std::string text = read_user_file(file, "model file");
  const StagedMjcf staged = stage_mjcf(text, fs::absolute(file).parent_path());
  Part part{mjcf_detail::parse_document(staged.xml, nullptr), {}, {}, std::move(source)};
  if (part.root.tag != "mujoco")
    throw Error(part.source + ": '" + file.string() + "' is not MJCF (root <" + part.root.tag +
                ">, expected <mujoco>)");
  normalize_part(part.root);
  part.keys = take_keys(part.root);
  return part;
}

Part parse_part(std::string_view xml, std::string source) {
  Part part{mjcf_detail::parse_document(xml, nullptr), {}, {}, std::move(source)};
  normalize_part(part.root);
  part.keys = take_keys(part.root);
  return part;
}

void prefix_part(Part& part, const std::string& prefix) {
  XmlNode& root = part.root;
  // assets named after their file get that name explicitly before it is prefixed
  for (auto& c : root.children) {
    if (c.tag != "asset") continue;
    for (auto& a : c.children) {
      if (a.has("name")) continue;
      if (const std::string* f = a.find("file"); f && a.tag != "skin")
        a.set("name", fs::path(*f).stem().string());
    }
  }
  // the part's main class must exist: its elements are given it explicitly below
  bool has_default = false;
  for (const auto& c : root.children) has_default = has_default || c.tag == "default";
  if (!has_default) {
    XmlNode main;
    main.tag = "default";
    root.children.push_back(std::move(main));
  }
  const std::string main_class = prefixed(prefix, "main");
  mjcf_detail::for_each_element(root, [&](XmlNode& e, XmlNode& parent) {
    for (auto& [key, value] : e.attrs) {
      if (value.empty() || (key != "name" && !kReferenceAttrs.count(key))) continue;
      const bool main = value == "main" && (key == "class" || key == "childclass");
      value = main ? main_class : prefixed(prefix, value);
    }
    if (e.tag == "default" && parent.tag == "mujoco" && !e.has("class")) e.set("class", main_class);
  });
  for (auto& c : root.children) {
    if (c.tag == "worldbody" || c.tag == "asset" || c.tag == "actuator" || c.tag == "equality" ||
        c.tag == "tendon" || c.tag == "contact")
      assign_main_class(c, main_class);
  }
  for (auto& key : part.keys) {
    key.name = prefixed(prefix, key.name);
    for (auto& [joint, values] : key.qpos) joint = prefixed(prefix, joint);
    for (auto& [actuator, value] : key.ctrl) actuator = prefixed(prefix, actuator);
  }
}

void strip_arena(XmlNode& root) {
  for (auto& c : root.children) {
    if (c.tag == "asset") {
      std::erase_if(c.children, [](const XmlNode& a) {
        const std::string* type = a.find("type");
        return a.tag == "texture" && type && *type == "skybox";
      });
    }
    if (c.tag != "worldbody") continue;
    std::vector<XmlNode> kept;
    for (auto& e : c.children) {
      const std::string* type = e.find("type");
      const bool plane = e.tag == "geom" && type && *type == "plane";
      if (!plane && e.tag != "light") kept.push_back(std::move(e));
    }
    c.children = std::move(kept);
  }
}

}  // namespace mjarm::scene_detail
