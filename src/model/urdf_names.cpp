#include "urdf_names.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <map>
#include <vector>

#include "mjarm/error.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm {

namespace {

/// What URDF allows in one element.
struct UrdfElement {
  std::vector<std::string> attributes;
  std::vector<std::string> children;
  std::vector<std::string> repeatable;  ///< children that may appear more than once
};

const std::map<std::string, UrdfElement, std::less<>>& urdf_elements() {
  static const std::map<std::string, UrdfElement, std::less<>> kElements = {
      {"link", {{"name"}, {"inertial", "visual", "collision"}, {"visual", "collision"}}},
      {"inertial", {{}, {"origin", "mass", "inertia"}, {}}},
      {"origin", {{"xyz", "rpy"}, {}, {}}},
      {"mass", {{"value"}, {}, {}}},
      {"inertia", {{"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}, {}, {}}},
      {"visual", {{"name"}, {"origin", "geometry", "material"}, {}}},
      {"collision", {{"name"}, {"origin", "geometry"}, {}}},
      {"geometry", {{}, {"box", "cylinder", "sphere", "capsule", "mesh"}, {}}},
      {"box", {{"size"}, {}, {}}},
      {"cylinder", {{"radius", "length"}, {}, {}}},
      {"sphere", {{"radius"}, {}, {}}},
      {"capsule", {{"radius", "length"}, {}, {}}},
      {"mesh", {{"filename", "scale"}, {}, {}}},
      {"material", {{"name"}, {"color", "texture"}, {}}},
      {"color", {{"rgba"}, {}, {}}},
      {"texture", {{"filename"}, {}, {}}},
      {"joint",
       {{"name", "type"},
        {"origin", "parent", "child", "axis", "calibration", "dynamics", "limit", "mimic",
         "safety_controller"},
        {}}},
      {"parent", {{"link"}, {}, {}}},
      {"child", {{"link"}, {}, {}}},
      {"axis", {{"xyz"}, {}, {}}},
      {"calibration", {{"rising", "falling", "reference_position"}, {}, {}}},
      {"dynamics", {{"damping", "friction"}, {}, {}}},
      {"limit", {{"lower", "upper", "effort", "velocity"}, {}, {}}},
      {"mimic", {{"joint", "multiplier", "offset"}, {}, {}}},
      {"safety_controller",
       {{"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}, {}, {}}}};
  return kElements;
}

// "drake:proximity_properties", "xmlns:xacro": another schema's names
bool namespaced(std::string_view name) { return name.find(':') != std::string_view::npos; }

// elements other simulators read inside a URDF's links, which MuJoCo ignores: a load warning
// says so (an error would refuse files those tools ship)
constexpr std::string_view kForeignElements[] = {
    "contact",                 // Bullet: friction, restitution, stiffness of a link
    "self_collision_checking"  // early ROS (urdfdom reads no more of it)
};

bool listed(const std::vector<std::string>& names, std::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

class UrdfNameCheck {
 public:
  UrdfNameCheck(const std::string& source, std::vector<std::string>& warnings)
      : source_(source), warnings_(warnings) {}

  /// Checks @p e, an element of kind @p rule, in @p where ("link 'arm'", "<visual> of …").
  void check(const tinyxml2::XMLElement& e, const UrdfElement& rule, const std::string& where) {
    for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next()) {
      if (!namespaced(a->Name()) && !listed(rule.attributes, a->Name()))
        fail(e, unknown_name_message("attribute", a->Name(), rule.attributes, where));
    }
    std::map<std::string, int, std::less<>> seen;  // child -> its first line
    const tinyxml2::XMLElement* shape = nullptr;   // a geometry's
    for (const auto* child = e.FirstChildElement(); child; child = child->NextSiblingElement()) {
      const std::string tag = child->Name();
      if (namespaced(tag)) continue;
      if (std::string_view(e.Name()) == "link" &&
          std::find(std::begin(kForeignElements), std::end(kForeignElements), tag) !=
              std::end(kForeignElements)) {
        warnings_.push_back("URDF " + source_ + " line " + std::to_string(child->GetLineNum()) +
                            ": <" + tag + "> in " + where +
                            " is not URDF (another simulator's); MuJoCo ignores it");
        continue;
      }
      if (!listed(rule.children, tag))
        fail(*child, unknown_name_message("element", tag, rule.children, where));
      if (std::string_view(e.Name()) == "geometry") {
        if (shape != nullptr)
          fail(*child, "a second shape <" + tag + "> in " + where + " (the first, <" +
                           shape->Name() + ">, at line " + std::to_string(shape->GetLineNum()) +
                           "): a geometry holds one");
        shape = child;
      }
      const auto [first, added] = seen.emplace(tag, child->GetLineNum());
      if (!added && !listed(rule.repeatable, tag))
        fail(*child, "a second <" + tag + "> in " + where + " (the first at line " +
                         std::to_string(first->second) + "): MuJoCo reads only the first");
      check(*child, urdf_elements().find(tag)->second, "<" + tag + "> of " + where);
    }
  }

 private:
  [[noreturn]] void fail(const tinyxml2::XMLElement& e, const std::string& message) const {
    throw Error("URDF " + source_ + " line " + std::to_string(e.GetLineNum()) + ": " + message);
  }

  const std::string& source_;
  std::vector<std::string>& warnings_;
};

}  // namespace

std::vector<std::string> check_urdf_names(std::string_view xml, const std::string& source) {
  std::vector<std::string> warnings;
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) return warnings;  // MuJoCo's
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::string_view(robot->Name()) != "robot") return warnings;
  UrdfNameCheck check(source, warnings);
  for (const auto* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag != "link" && tag != "joint" && tag != "material") continue;
    const char* name = e->Attribute("name");
    check.check(*e, urdf_elements().find(tag)->second,
                tag + " '" + (name != nullptr ? name : "") + "'");
  }
  return warnings;
}

}  // namespace mjarm
