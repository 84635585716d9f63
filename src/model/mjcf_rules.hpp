#pragma once
// Rule table types of the MJCF translator and the custom rules it refers to.

#include <string>
#include <string_view>

#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

/// What becomes of a MuJoCo 3.x attribute.
enum class Action {
  kDrop,    ///< remove it (it does not change the dynamics), with a warning
  kDropIf,  ///< remove it when its value is one of `arg` (2.2.2's behaviour), else throw
  kRename,  ///< write its value under the 2.2.2 name `arg`
  kReject,  ///< throw: it changes the dynamics and 2.2.2 cannot express it
  kCustom,  ///< call `fn`
};

/// What the rules can see besides the element itself.
struct RuleEnv {
  const XmlNode& root;
  Context& ctx;
};

/// A custom rule: gets the element, the attribute and its value (still present on `e`).
using RuleFn = void (*)(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);

/// One row of the attribute table: applies to every tag in `tags` and every attribute in `attrs`
/// (both space-separated lists).
struct AttrRule {
  std::string_view tags;
  std::string_view attrs;
  Action action;
  std::string_view arg;
  std::string_view why;
  RuleFn fn = nullptr;
};

/// Child elements (space-separated `tags`) of a `parent` element that are dropped with a warning.
struct ElementRule {
  std::string_view parent;
  std::string_view tags;
  std::string_view why;
};

// custom rules (mjcf_rule_fns.cpp)
void rule_integrator(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_o_friction(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_spring_damper(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_eulerdamp(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_mesh_inertia(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_gravcomp(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_polynomial(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_springlength(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_geom_type(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_light_type(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);
void rule_actearly(XmlNode& e, const std::string& key, const std::string& value, RuleEnv& env);

}  // namespace mjarm::mjcf_detail
