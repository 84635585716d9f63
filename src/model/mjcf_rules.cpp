// The table of MuJoCo 3.x attributes and elements and what becomes of them in MuJoCo 2.2.2.
// Adding a rule is one line in kAttrRules or kElementRules.

#include "mjcf_rules.hpp"

#include <algorithm>

namespace mjarm::mjcf_detail {

namespace {

constexpr std::string_view kVisual = "rendering only";
constexpr std::string_view kActuators =
    "general motor position velocity intvelocity damper cylinder muscle adhesion";
constexpr std::string_view kSensors =
    "touch accelerometer velocimeter gyro force torque magnetometer rangefinder jointpos jointvel "
    "tendonpos tendonvel actuatorpos actuatorvel actuatorfrc ballquat ballangvel jointlimitpos "
    "jointlimitvel jointlimitfrc tendonlimitpos tendonlimitvel tendonlimitfrc framepos framequat "
    "framexaxis frameyaxis framezaxis framelinvel frameangvel framelinacc frameangacc subtreecom "
    "subtreelinvel subtreeangmom clock user";

// clang-format off
const AttrRule kAttrRules[] = {
  // compiler
  {"compiler", "alignfree", Action::kDropIf, "false", "it changes what qpos means"},
  {"compiler", "saveinertial", Action::kDrop, "", "it only affects saving"},
  {"compiler", "conflict", Action::kDrop, "", "it only affects <attach>"},
  // option
  {"option", "integrator", Action::kCustom, "", "", rule_integrator},
  {"option", "ls_iterations", Action::kDrop, "", "2.2.2 uses fixed line-search settings"},
  {"option", "ls_tolerance", Action::kDrop, "", "2.2.2 uses fixed line-search settings"},
  {"option", "ccd_iterations", Action::kRename, "mpr_iterations", "2.2.2's name"},
  {"option", "ccd_tolerance", Action::kRename, "mpr_tolerance", "2.2.2's name"},
  {"option", "sdf_iterations", Action::kDrop, "", "2.2.2 has no SDF collisions"},
  {"option", "sdf_initpoints", Action::kDrop, "", "2.2.2 has no SDF collisions"},
  {"option", "sleep_tolerance", Action::kDrop, "", "2.2.2 has no body sleeping"},
  {"option", "o_friction", Action::kCustom, "", "", rule_o_friction},
  {"option", "actuatorgroupdisable", Action::kReject, "", "it disables actuators"},
  {"flag", "spring", Action::kCustom, "", "", rule_spring_damper},
  {"flag", "damper", Action::kCustom, "", "", rule_spring_damper},
  {"flag", "eulerdamp", Action::kCustom, "", "", rule_eulerdamp},
  {"flag", "island", Action::kDrop, "", "constraint islands only speed up the solver"},
  {"flag", "nativeccd", Action::kDrop, "", "2.2.2 always uses libccd, as nativeccd=\"disable\""},
  {"flag", "midphase", Action::kDrop, "", "the BVH midphase only speeds up collision detection"},
  {"flag", "autoreset", Action::kDrop, "", "it is a viewer-level reset on divergence"},
  {"flag", "invdiscrete", Action::kDropIf, "disable", "it changes mj_inverse"},
  {"flag", "sleep", Action::kDropIf, "disable", "sleeping bodies change the simulation"},
  {"flag", "diagexact", Action::kDropIf, "disable", "it changes the constraint solver"},
  // size, visual
  {"size", "memory", Action::kDrop, "", "2.2.2 sizes its buffers from njmax (500), nconmax (100) "
                                        "and nstack; set those if it reports overflows"},
  {"global", "orthographic realtime ellipsoidinertia bvactive cameraid", Action::kDrop, "",
   kVisual},
  {"scale", "frustum", Action::kDrop, "", kVisual},
  {"rgba", "frustum bv bvactive", Action::kDrop, "", kVisual},
  // assets
  {"mesh", "content_type", Action::kDrop, "", "2.2.2 infers the type from the file extension"},
  {"mesh", "maxhullvert", Action::kDrop, "", "2.2.2 builds the convex hull from all vertices"},
  {"mesh", "inertia", Action::kCustom, "", "", rule_mesh_inertia},
  {"mesh", "material", Action::kDrop, "", kVisual},
  {"hfield", "content_type", Action::kDrop, "", "2.2.2 infers the type from the file extension"},
  {"texture", "colorspace nchannel", Action::kDrop, "", kVisual},
  {"texture", "content_type", Action::kDrop, "", "2.2.2 infers the type from the file extension"},
  {"material", "metallic roughness", Action::kDrop, "", kVisual},
  // body tree
  {"body", "gravcomp", Action::kCustom, "", "", rule_gravcomp},
  {"body", "sleep simple", Action::kDrop, "", "it only affects performance"},
  {"joint", "actuatorgravcomp", Action::kDrop, "", "2.2.2 has no gravity compensation"},
  {"joint tendon spatial fixed", "stiffness damping", Action::kCustom, "", "", rule_polynomial},
  {"tendon spatial fixed", "springlength", Action::kCustom, "", "", rule_springlength},
  {"tendon spatial fixed", "armature", Action::kDropIf, "0", "tendon armature adds inertia"},
  {"freejoint", "align", Action::kDropIf, "false auto", "it changes what qpos means"},
  {"geom", "surfacevel", Action::kDropIf, "0", "surface velocity changes contacts"},
  {"geom pair", "adhesion", Action::kDropIf, "0", "geom adhesion changes contacts"},
  {"geom", "type", Action::kCustom, "", "", rule_geom_type},
  {"pair", "solreffriction", Action::kDropIf, "0 0", "a separate friction solref changes contacts"},
  {"camera", "projection", Action::kDrop, "", kVisual},
  {"camera", "resolution output focal focalpixel principal principalpixel sensorsize",
   Action::kDrop, "", kVisual},
  {"light", "type", Action::kCustom, "", "", rule_light_type},
  {"light", "bulbradius intensity range softness texture", Action::kDrop, "", kVisual},
  // actuators
  {kActuators, "actearly", Action::kCustom, "", "", rule_actearly},
  {kActuators, "actdim", Action::kDropIf, "-1 1", "extra activation states need a user dynamics"},
  {kActuators, "nsample delay", Action::kDropIf, "0", "delayed actuation changes the dynamics"},
  {kActuators, "interp", Action::kDrop, "", "it only applies to delayed actuation"},
  {kActuators, "damping armature", Action::kDropIf, "0", "they change the dynamics"},
  {"muscle", "tausmooth", Action::kDropIf, "0", "smoothed muscle activation changes the dynamics"},
  // sensors
  {kSensors, "nsample delay interval", Action::kDropIf, "0", "delays change the readings"},
  {kSensors, "interp", Action::kDrop, "", "it only applies to delayed sensors"},
  {"rangefinder", "data", Action::kDropIf, "dist", "2.2.2 rangefinders only measure distance"},
  {"rangefinder", "camera", Action::kReject, "", "2.2.2 rangefinders need a site"},
};

const ElementRule kElementRules[] = {
  {"sensor", "camprojection jointactuatorfrc tendonactuatorfrc insidesite distance normal fromto "
             "contact e_potential e_kinetic tactile plugin",
   "this sensor type is not in MuJoCo 2.2.2; sensors do not change the dynamics"},
  {"material", "layer", "material layers are rendering only"},
};
// clang-format on

bool listed(std::string_view list, std::string_view word) {
  while (!list.empty()) {
    const std::size_t sp = list.find(' ');
    if (list.substr(0, sp) == word) return true;
    if (sp == std::string_view::npos) break;
    list.remove_prefix(sp + 1);
  }
  return false;
}

// numeric lists compare by value ("0" == "0.0" == "0 0"), anything else as text
bool same_value(const XmlNode& e, std::string_view key, const std::string& value,
                std::string_view accepted) {
  if (value == accepted) return true;
  try {
    const std::vector<double> a = parse_numbers(e, key, value);
    const std::vector<double> b = parse_numbers(e, key, accepted);
    if (a.empty() || b.empty()) return false;
    // a single accepted number stands for a list of that number
    return std::all_of(a.begin(), a.end(), [&](double x) { return b.size() == 1 && x == b[0]; }) ||
           a == b;
  } catch (...) {
    return false;
  }
}

bool accepted_value(const XmlNode& e, std::string_view key, const std::string& value,
                    std::string_view accepted) {
  while (!accepted.empty()) {
    const std::size_t sp = accepted.find(' ');
    const std::string_view word = accepted.substr(0, sp);
    // "0 0" style lists are given whole, words one by one
    if (same_value(e, key, value, accepted) || same_value(e, key, value, word)) return true;
    if (sp == std::string_view::npos) break;
    accepted.remove_prefix(sp + 1);
  }
  return false;
}

void apply_attr_rule(const AttrRule& rule, XmlNode& e, const std::string& key, RuleEnv& env) {
  const std::string value = *e.find(key);
  const std::string what = key + "=\"" + value + "\" is MuJoCo 3.x";
  switch (rule.action) {
    case Action::kDrop:
      e.erase(key);
      env.ctx.warn(e, what + " (" + std::string(rule.why) + "); dropped");
      return;
    case Action::kDropIf:
      if (!accepted_value(e, key, value, rule.arg)) {
        fail(e, what + " and cannot be translated (" + std::string(rule.why) + ")");
      }
      e.erase(key);
      env.ctx.warn(e, what + "; dropped (this value matches MuJoCo 2.2.2's behaviour)");
      return;
    case Action::kRename:
      e.erase(key);
      e.set(rule.arg, value);
      env.ctx.warn(
          e, what + "; written as " + std::string(rule.arg) + " (" + std::string(rule.why) + ")");
      return;
    case Action::kReject:
      fail(e, what + " and cannot be translated (" + std::string(rule.why) + ")");
    case Action::kCustom:
      rule.fn(e, key, value, env);
      return;
  }
}

void walk(XmlNode& e, RuleEnv& env) {
  // element rules: drop children MuJoCo 2.2.2 has no counterpart for
  std::vector<XmlNode> kept;
  for (auto& c : e.children) {
    const auto drop = std::find_if(
        std::begin(kElementRules), std::end(kElementRules),
        [&](const ElementRule& r) { return r.parent == e.tag && listed(r.tags, c.tag); });
    if (drop != std::end(kElementRules)) {
      env.ctx.warn(c, "<" + c.tag + "> dropped: " + std::string(drop->why));
    } else {
      kept.push_back(std::move(c));
    }
  }
  e.children = std::move(kept);

  // attribute rules; a custom rule may consume further attributes, so re-check presence
  std::vector<std::string> keys;
  for (const auto& kv : e.attrs) keys.push_back(kv.first);
  for (const auto& key : keys) {
    if (!e.has(key)) continue;
    for (const AttrRule& rule : kAttrRules) {
      if (listed(rule.tags, e.tag) && listed(rule.attrs, key)) {
        apply_attr_rule(rule, e, key, env);
        break;
      }
    }
  }
  for (auto& c : e.children) walk(c, env);
}

}  // namespace

void apply_rules(XmlNode& root, Context& ctx) {
  RuleEnv env{root, ctx};
  walk(root, env);
}

}  // namespace mjarm::mjcf_detail
