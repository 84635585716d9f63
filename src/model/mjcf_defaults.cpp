// Snapshot of MJCF <default> classes and attribute lookup through the class hierarchy.

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

bool is_actuator_tag(std::string_view tag) {
  return tag == "general" || tag == "motor" || tag == "position" || tag == "velocity" ||
         tag == "intvelocity" || tag == "damper" || tag == "cylinder" || tag == "muscle" ||
         tag == "adhesion";
}

std::string_view default_kind(std::string_view tag) {
  if (tag == "spatial" || tag == "fixed") return "tendon";
  // every actuator shortcut of a class writes into the class's single actuator default
  if (is_actuator_tag(tag)) return "actuator";
  return tag;
}

namespace {

void collect(XmlNode& node, const std::string& parent, std::vector<Defaults::Class>& classes) {
  std::string name;
  if (const std::string* c = node.find("class")) {
    name = *c;
  } else if (parent.empty()) {
    name = "main";
  } else {
    fail(node, "a nested <default> needs a class attribute");
  }
  classes.push_back({name, parent, &node});
  for (auto& child : node.children) {
    if (child.tag == "default") collect(child, name, classes);
  }
}

}  // namespace

Defaults::Defaults(XmlNode& root) {
  for (auto& child : root.children) {
    if (child.tag == "default") collect(child, "", classes_);
  }
  for (std::size_t i = 0; i < classes_.size(); ++i) {
    const Class& c = classes_[i];
    if (index_.count(c.name) && c.name != "main") fail(*c.node, "repeated default class");
    index_[c.name] = i;
    auto& kinds = values_[c.name];
    for (const auto& el : c.node->children) {
      if (el.tag == "default") continue;
      auto& attrs = kinds[std::string(default_kind(el.tag))];
      for (const auto& [k, v] : el.attrs) attrs[k] = v;
    }
  }
}

std::optional<std::string> Defaults::lookup(const std::string& cls, std::string_view kind,
                                            std::string_view attr) const {
  std::string current = has(cls) ? cls : std::string("main");
  for (int guard = 0; guard < 1000 && !current.empty(); ++guard) {
    const auto cit = values_.find(current);
    if (cit != values_.end()) {
      const auto kit = cit->second.find(std::string(kind));
      if (kit != cit->second.end()) {
        const auto ait = kit->second.find(std::string(attr));
        if (ait != kit->second.end()) return ait->second;
      }
    }
    const auto it = index_.find(current);
    if (it == index_.end()) break;
    current = classes_[it->second].parent;
  }
  return std::nullopt;
}

}  // namespace mjarm::mjcf_detail
