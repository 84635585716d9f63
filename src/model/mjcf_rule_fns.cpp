// Custom rules of the MJCF translator's attribute table (mjcf_rules.cpp).

#include <algorithm>

#include "mjcf_rules.hpp"

namespace mjarm::mjcf_detail {

namespace {

std::string quoted(const std::string& key, const std::string& value) {
  return key + "=\"" + value + "\"";
}

bool override_enabled(const XmlNode& root) {
  for (const auto& opt : root.children) {
    if (opt.tag != "option") continue;
    for (const auto& flag : opt.children) {
      const std::string* v = flag.tag == "flag" ? flag.find("override") : nullptr;
      if (v && *v == "enable") return true;
    }
  }
  return false;
}

}  // namespace

void rule_integrator(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  if (value != "implicitfast") return;
  // 2.2.2's implicit also keeps the Coriolis derivatives implicitfast leaves out: as stable, a
  // little more work per step
  e.set(key, "implicit");
  env.ctx.warn(e, quoted(key, value) + " is MuJoCo 3.x; using \"implicit\"");
}

void rule_o_friction(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  if (override_enabled(env.root)) {
    fail(e, quoted(key, value) +
                " is MuJoCo 3.x and overrides contact friction (flag override is "
                "enabled); 2.2.2 cannot express it");
  }
  e.erase(key);
  env.ctx.warn(e, quoted(key, value) +
                      " is MuJoCo 3.x; dropped (only used with flag override, "
                      "which is disabled)");
}

void rule_spring_damper(XmlNode& e, const std::string& /*key*/, const std::string& /*value*/,
                        RuleEnv& env) {
  // 3.x split 2.2.2's passive flag in two; both together map back onto it
  const std::string spring = e.find("spring") ? *e.find("spring") : "enable";
  const std::string damper = e.find("damper") ? *e.find("damper") : "enable";
  if (spring != damper) {
    fail(e, "spring=\"" + spring + "\" with damper=\"" + damper +
                "\" is MuJoCo 3.x; 2.2.2 can only switch springs and dampers together (passive)");
  }
  e.erase("spring");
  e.erase("damper");
  if (spring == "disable") {
    const std::string* passive = e.find("passive");
    if (passive && *passive != "disable") fail(e, "passive=\"enable\" contradicts spring/damper");
    e.set("passive", "disable");
    env.ctx.warn(e, "spring/damper=\"disable\" are MuJoCo 3.x; written as passive=\"disable\"");
  } else {
    env.ctx.warn(e, "spring/damper=\"enable\" are MuJoCo 3.x; dropped (2.2.2's default)");
  }
}

void rule_eulerdamp(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  e.erase(key);
  if (value == "enable") {
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped (2.2.2's Euler integrator "
                        "always treats joint damping implicitly)");
  } else {
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped: 2.2.2's Euler integrator "
                        "always treats joint damping implicitly");
  }
}

void rule_mesh_inertia(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  if (value == "legacy") {
    e.erase(key);
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped (2.2.2 computes the legacy "
                        "mesh inertia)");
  } else if (value == "convex") {
    e.erase(key);
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped: 2.2.2 computes the legacy "
                        "mesh inertia, equal to the convex one for convex meshes");
  } else {
    fail(e, quoted(key, value) + " is MuJoCo 3.x; 2.2.2 computes only the legacy mesh inertia");
  }
}

void rule_gravcomp(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  e.erase(key);
  const std::vector<double> v = parse_numbers(e, key, value);
  if (v.size() == 1 && v[0] == 0) {
    env.ctx.warn(e, quoted(key, value) + " is MuJoCo 3.x; dropped (no compensation asked)");
  } else {
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped: 2.2.2 has no gravity "
                        "compensation, so this body's weight now loads its "
                        "joints (compensate in the controller)");
  }
}

void rule_polynomial(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  // 3.x accepts polynomial coefficients after the linear one
  const std::vector<double> v = parse_numbers(e, key, value);
  if (v.size() <= 1) return;
  if (!std::all_of(v.begin() + 1, v.end(), [](double x) { return x == 0; })) {
    fail(e, quoted(key, value) + " is a MuJoCo 3.x nonlinear " + key + "; 2.2.2 is linear only");
  }
  e.set(key, format_numbers(std::span<const double>(v.data(), 1)));
  env.ctx.warn(e, quoted(key, value) + " has MuJoCo 3.x zero higher-order terms; written as " +
                      quoted(key, *e.find(key)));
}

void rule_springlength(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  const std::vector<double> v = parse_numbers(e, key, value);
  if (v.size() <= 1) return;
  if (v.size() != 2 || v[0] != v[1]) {
    fail(e, quoted(key, value) + " is a MuJoCo 3.x dead-band spring; 2.2.2 has one rest length");
  }
  e.set(key, format_numbers(std::span<const double>(v.data(), 1)));
  env.ctx.warn(e, quoted(key, value) + " is MuJoCo 3.x; written as " + quoted(key, *e.find(key)));
}

void rule_geom_type(XmlNode& e, const std::string& key, const std::string& value,
                    RuleEnv& /*env*/) {
  if (value == "sdf") fail(e, quoted(key, value) + " is MuJoCo 3.x; 2.2.2 has no SDF geoms");
}

void rule_light_type(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  e.erase(key);
  if (value == "directional") {
    const std::string* d = e.find("directional");
    if (d && *d != "true") fail(e, "type=\"directional\" contradicts directional=\"false\"");
    e.set("directional", "true");
    env.ctx.warn(e, quoted(key, value) + " is MuJoCo 3.x; written as directional=\"true\"");
  } else {
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped (rendering only; 2.2.2 lights "
                        "are spot lights)");
  }
}

void rule_actearly(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env) {
  e.erase(key);
  if (value == "true") {
    env.ctx.warn(e, quoted(key, value) +
                        " is MuJoCo 3.x; dropped: 2.2.2 computes the force from "
                        "the current activation (one step behind for actuators "
                        "with dynamics)");
  } else {
    env.ctx.warn(e, quoted(key, value) + " is MuJoCo 3.x; dropped (2.2.2's behaviour)");
  }
}

}  // namespace mjarm::mjcf_detail
