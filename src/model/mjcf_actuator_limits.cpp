// MuJoCo 3.x joint / tendon actuatorfrcrange: a clamp on the total actuator force at the joint.
// With one actuator of gear g it equals an actuator forcerange of actuatorfrcrange / g.

#include <algorithm>

#include "mjcf_actuator_record.hpp"

namespace mjarm::mjcf_detail {

namespace {

using Drives = std::map<std::string, std::vector<XmlNode*>>;

std::optional<std::string> effective(const XmlNode& n, const std::string& cls,
                                     std::string_view kind, const char* key,
                                     const Defaults& defaults) {
  if (const std::string* v = n.find(key)) return *v;
  return defaults.lookup(cls, kind, key);
}

void clamp_target(XmlNode& target, const std::string& cls, const Drives& drives, Context& ctx,
                  const Defaults& defaults) {
  const std::string_view kind = default_kind(target.tag);
  const auto range = effective(target, cls, kind, "actuatorfrcrange", defaults);
  const auto limited = effective(target, cls, kind, "actuatorfrclimited", defaults);
  const bool own = target.has("actuatorfrcrange") || target.has("actuatorfrclimited");
  target.erase("actuatorfrcrange");
  target.erase("actuatorfrclimited");
  if (!range || limited == "false") {
    if (own)
      ctx.warn(target,
               "actuatorfrcrange/actuatorfrclimited are MuJoCo 3.x and clamp "
               "nothing here; dropped");
    return;
  }
  const std::vector<double> r = parse_numbers(target, "actuatorfrcrange", *range);
  if (r.size() != 2 || r[0] > r[1]) fail(target, "actuatorfrcrange must be two increasing numbers");

  const std::string* name = target.find("name");
  const auto it = name ? drives.find(*name) : drives.end();
  if (it == drives.end() || it->second.empty()) {
    ctx.warn(target,
             "actuatorfrcrange is MuJoCo 3.x; no actuator drives this " + target.tag + ", dropped");
    return;
  }
  if (it->second.size() > 1) {
    fail(target, "actuatorfrcrange clamps the sum of " + std::to_string(it->second.size()) +
                     " actuators; MuJoCo 2.2.2 has no equivalent");
  }
  XmlNode& act = *it->second.front();
  const std::string* ac = act.find("class");
  const std::string acls = ac ? *ac : std::string("main");
  const auto gear_text = effective(act, acls, "actuator", "gear", defaults);
  const double g = gear_text ? parse_numbers(act, "gear", *gear_text).at(0) : 1.0;
  if (g == 0) {
    ctx.warn(target, "actuatorfrcrange is MuJoCo 3.x; its actuator has zero gear, dropped");
    return;
  }
  double lo = r[0] / g, hi = r[1] / g;
  if (g < 0) std::swap(lo, hi);
  // intersect with a force range the actuator already enforces
  const auto fl = effective(act, acls, "actuator", "forcelimited", defaults);
  const auto fr = effective(act, acls, "actuator", "forcerange", defaults);
  if (fr && (fl == "true" || !fl || fl == "auto")) {
    const std::vector<double> f = parse_numbers(act, "forcerange", *fr);
    if (f.size() != 2) fail(act, "forcerange needs 2 numbers");
    lo = std::max(lo, f[0]);
    hi = std::min(hi, f[1]);
    if (lo > hi) fail(target, "actuatorfrcrange and the actuator forcerange do not overlap");
  }
  const std::string text = format_numbers(std::array<double, 2>{lo, hi});
  act.set("forcerange", text);
  act.set("forcelimited", "true");
  ctx.warn(target, "actuatorfrcrange=\"" + *range + "\" is MuJoCo 3.x; applied as forcerange=\"" +
                       text + "\" of its only actuator " + label(act));
}

void walk_joints(XmlNode& body, const std::string& cc, const Drives& drives, Context& ctx,
                 const Defaults& defaults) {
  const std::string* own = body.tag == "body" ? body.find("childclass") : nullptr;
  const std::string childclass = own ? *own : cc;
  for (auto& c : body.children) {
    if (c.tag == "joint") {
      const std::string* cls = c.find("class");
      clamp_target(c, cls ? *cls : (childclass.empty() ? "main" : childclass), drives, ctx,
                   defaults);
    } else if (c.tag == "body") {
      walk_joints(c, childclass, drives, ctx, defaults);
    }
  }
}

}  // namespace

void translate_actuator_force_limits(XmlNode& root, Context& ctx, const Defaults& defaults,
                                     const TargetIndex& /*targets*/) {
  Drives joints, tendons;
  for (auto& section : root.children) {
    if (section.tag != "actuator") continue;
    for (auto& a : section.children) {
      for (const char* key : {"joint", "jointinparent"}) {
        if (const std::string* n = a.find(key)) joints[*n].push_back(&a);
      }
      if (const std::string* n = a.find("tendon")) tendons[*n].push_back(&a);
    }
  }
  for (auto& c : root.children) {
    if (c.tag == "worldbody") walk_joints(c, "", joints, ctx, defaults);
    if (c.tag != "tendon") continue;
    for (auto& t : c.children) {
      const std::string* cls = t.find("class");
      clamp_target(t, cls ? *cls : "main", tendons, ctx, defaults);
    }
  }
  // the class values were applied to each joint / tendon above
  for (const auto& cls : defaults.classes()) {
    for (auto& e : cls.node->children) {
      if (e.tag != "joint" && e.tag != "tendon") continue;
      const bool range = e.erase("actuatorfrcrange");
      const bool limited = e.erase("actuatorfrclimited");
      if (range || limited) {
        ctx.warn(e, "actuatorfrcrange is MuJoCo 3.x; applied to each " + e.tag + " of class '" +
                        cls.name + "' instead");
      }
    }
  }
}

}  // namespace mjarm::mjcf_detail
