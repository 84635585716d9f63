#include "scene_elements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>
#include <vector>

#include "mjarm/closest_names.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "spec_attributes.hpp"

namespace mjarm::scene_detail {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

constexpr std::string_view kBodyTags[] = {"body", "joint", "geom", "site", "camera", "light"};
constexpr std::string_view kActuatorTags[] = {"general", "motor", "position", "velocity"};

struct SensorTag {
  std::string_view tag;
  mjtSensor type;
};
constexpr SensorTag kSensorTags[] = {{"jointpos", mjSENS_JOINTPOS},
                                     {"jointvel", mjSENS_JOINTVEL},
                                     {"actuatorpos", mjSENS_ACTUATORPOS},
                                     {"actuatorvel", mjSENS_ACTUATORVEL},
                                     {"actuatorfrc", mjSENS_ACTUATORFRC},
                                     {"framepos", mjSENS_FRAMEPOS},
                                     {"framequat", mjSENS_FRAMEQUAT},
                                     {"framexaxis", mjSENS_FRAMEXAXIS},
                                     {"frameyaxis", mjSENS_FRAMEYAXIS},
                                     {"framezaxis", mjSENS_FRAMEZAXIS},
                                     {"framelinvel", mjSENS_FRAMELINVEL},
                                     {"frameangvel", mjSENS_FRAMEANGVEL},
                                     {"framelinacc", mjSENS_FRAMELINACC},
                                     {"frameangacc", mjSENS_FRAMEANGACC},
                                     {"touch", mjSENS_TOUCH},
                                     {"force", mjSENS_FORCE},
                                     {"torque", mjSENS_TORQUE},
                                     {"accelerometer", mjSENS_ACCELEROMETER},
                                     {"velocimeter", mjSENS_VELOCIMETER},
                                     {"gyro", mjSENS_GYRO},
                                     {"magnetometer", mjSENS_MAGNETOMETER},
                                     {"subtreecom", mjSENS_SUBTREECOM},
                                     {"subtreelinvel", mjSENS_SUBTREELINVEL},
                                     {"subtreeangmom", mjSENS_SUBTREEANGMOM},
                                     {"clock", mjSENS_CLOCK}};

// the objects MJCF names by attribute: a sensor's object, an actuator's transmission
struct ObjectAttribute {
  std::string_view name;
  mjtObj type;
};
constexpr ObjectAttribute kObjectTypes[] = {{"body", mjOBJ_BODY},         {"xbody", mjOBJ_XBODY},
                                            {"geom", mjOBJ_GEOM},         {"site", mjOBJ_SITE},
                                            {"camera", mjOBJ_CAMERA},     {"joint", mjOBJ_JOINT},
                                            {"actuator", mjOBJ_ACTUATOR}, {"tendon", mjOBJ_TENDON}};
struct Transmission {
  std::string_view name;
  mjtTrn type;
};
constexpr Transmission kTransmissions[] = {{"joint", mjTRN_JOINT},
                                           {"jointinparent", mjTRN_JOINTINPARENT},
                                           {"tendon", mjTRN_TENDON},
                                           {"site", mjTRN_SITE},
                                           {"body", mjTRN_BODY}};

const SensorTag* sensor_tag(std::string_view tag) {
  for (const SensorTag& s : kSensorTags)
    if (s.tag == tag) return &s;
  return nullptr;
}

bool is_actuator(std::string_view tag) {
  for (std::string_view t : kActuatorTags)
    if (t == tag) return true;
  return false;
}

double number(std::string_view value, const std::string& what, std::string_view attribute) {
  const auto v = number_from_text(std::string(value));
  if (!v || !std::isfinite(*v)) {
    throw Error(what + ": " + std::string(attribute) + " must be a finite number, got '" +
                std::string(value) + "'");
  }
  return *v;
}

mjtObj object_type(std::string_view value, const std::string& what, std::string_view attribute) {
  std::vector<std::string> names;
  for (const ObjectAttribute& o : kObjectTypes) {
    if (o.name == value) return o.type;
    names.emplace_back(o.name);
  }
  throw Error(what + ": " + std::string(attribute) + " '" + std::string(value) +
              "' is not an object type; types: " + joined(names));
}

// the attributes of an actuator tag that set its gains (MJCF's shortcuts), the rest in order
void make_actuator(mjsActuator& a, const ElementSpec& e, const std::string& what) {
  double kp = 1.0, kv = e.tag == "velocity" ? 1.0 : 0.0;
  for (const auto& [attribute, value] : e.attributes) {
    const std::string& key = attribute;  // (a lambda cannot capture a structured binding)
    if (attribute == "kp" && e.tag == "position") {
      kp = number(value, what, attribute);
    } else if (attribute == "kv" && (e.tag == "position" || e.tag == "velocity")) {
      kv = number(value, what, attribute);
    } else if (const auto* t = std::find_if(std::begin(kTransmissions), std::end(kTransmissions),
                                            [&](const Transmission& x) { return x.name == key; });
               t != std::end(kTransmissions)) {
      a.trntype = t->type;
      mjs_setString(a.target, value.c_str());
    } else {
      write_attribute(*a.element, attribute, value, what);
    }
  }
  // MJCF's shortcuts, as its parser sets them: force = gain · ctrl + bias
  if (e.tag == "motor") {
    a.gaintype = mjGAIN_FIXED;
    a.gainprm[0] = 1.0;
    a.biastype = mjBIAS_NONE;
  } else if (e.tag == "position") {
    a.gaintype = mjGAIN_FIXED;
    a.gainprm[0] = kp;
    a.biastype = mjBIAS_AFFINE;
    a.biasprm[1] = -kp;
    a.biasprm[2] = -kv;
  } else if (e.tag == "velocity") {
    a.gaintype = mjGAIN_FIXED;
    a.gainprm[0] = kv;
    a.biastype = mjBIAS_AFFINE;
    a.biasprm[2] = -kv;
  }
}

void make_sensor(mjsSensor& s, const SensorTag& tag, const ElementSpec& e,
                 const std::string& what) {
  s.type = tag.type;
  for (const auto& [attribute, value] : e.attributes) {
    const std::string& key = attribute;  // (a lambda cannot capture a structured binding)
    if (attribute == "objtype") {
      s.objtype = object_type(value, what, attribute);
    } else if (attribute == "objname") {
      mjs_setString(s.objname, value.c_str());
    } else if (attribute == "reftype") {
      s.reftype = object_type(value, what, attribute);
    } else if (attribute == "refname") {
      mjs_setString(s.refname, value.c_str());
    } else if (const auto* o =
                   std::find_if(std::begin(kObjectTypes), std::end(kObjectTypes),
                                [&](const ObjectAttribute& x) { return x.name == key; });
               o != std::end(kObjectTypes) && o->type != mjOBJ_XBODY && o->type != mjOBJ_GEOM &&
               o->type != mjOBJ_CAMERA) {
      s.objtype = o->type;
      mjs_setString(s.objname, value.c_str());
    } else {
      write_attribute(*s.element, attribute, value, what);
    }
  }
}

// "geom.rgba" → the default's geom
mjsElement* default_part(mjsDefault& d, std::string_view element, const std::string& what) {
  const std::pair<std::string_view, mjsElement*> parts[] = {
      {"joint", d.joint->element},       {"geom", d.geom->element},
      {"site", d.site->element},         {"camera", d.camera->element},
      {"light", d.light->element},       {"mesh", d.mesh->element},
      {"material", d.material->element}, {"pair", d.pair->element},
      {"equality", d.equality->element}, {"tendon", d.tendon->element},
      {"actuator", d.actuator->element}};
  std::vector<std::string> names;
  for (const auto& [name, part] : parts) {
    if (name == element) return part;
    names.emplace_back(name);
  }
  throw Error(what + ": a default's attribute is <element>.<attribute> with element one of " +
              joined(names) + "; got '" + std::string(element) + "'");
}

}  // namespace

std::optional<std::string_view> element_kind(std::string_view tag) {
  for (std::string_view t : kBodyTags)
    if (t == tag) return t;
  if (is_actuator(tag)) return "actuator";
  if (sensor_tag(tag) != nullptr) return "sensor";
  if (tag == "default") return "default";
  return std::nullopt;
}

std::vector<std::string> all_tags() {
  std::vector<std::string> tags(std::begin(kBodyTags), std::end(kBodyTags));
  tags.insert(tags.end(), std::begin(kActuatorTags), std::end(kActuatorTags));
  for (const SensorTag& s : kSensorTags) tags.emplace_back(s.tag);
  tags.emplace_back("default");
  return tags;
}

void make_element(mjSpec& spec, const ElementSpec& e, mjsBody* parent, mjsDefault* def,
                  const std::string& what) {
  const auto apply_all = [&](mjsElement& element) {
    for (const auto& [attribute, value] : e.attributes)
      write_attribute(element, attribute, value, what);
  };
  mjsElement* made = nullptr;
  if (e.tag == "body") {
    made = mjs_addBody(parent, def)->element;
  } else if (e.tag == "joint") {
    made = mjs_addJoint(parent, def)->element;
  } else if (e.tag == "geom") {
    made = mjs_addGeom(parent, def)->element;
  } else if (e.tag == "site") {
    made = mjs_addSite(parent, def)->element;
  } else if (e.tag == "camera") {
    made = mjs_addCamera(parent, def)->element;
  } else if (e.tag == "light") {
    made = mjs_addLight(parent, def)->element;
  } else if (is_actuator(e.tag)) {
    mjsActuator* a = mjs_addActuator(&spec, def);
    mjs_setName(a->element, e.name.c_str());
    make_actuator(*a, e, what);
    return;
  } else if (const SensorTag* tag = sensor_tag(e.tag)) {
    mjsSensor* s = mjs_addSensor(&spec);
    mjs_setName(s->element, e.name.c_str());
    make_sensor(*s, *tag, e, what);
    return;
  } else if (e.tag == "default") {
    mjsDefault* d = mjs_addDefault(&spec, e.name.c_str(), def);
    if (d == nullptr) throw Error(what + ": MuJoCo refused the class");
    for (const auto& [attribute, value] : e.attributes) {
      const auto dot = attribute.find('.');
      if (dot == std::string::npos)
        throw Error(what + ": a default's attribute is <element>.<attribute>, got '" + attribute +
                    "'");
      write_attribute(*default_part(*d, std::string_view(attribute).substr(0, dot), what),
                      std::string_view(attribute).substr(dot + 1), value, what);
    }
    return;
  } else {
    throw Error(what + ": " + unknown_name_message("tag", e.tag, all_tags()));
  }
  mjs_setName(made, e.name.c_str());
  apply_all(*made);
}

SpecPtr with_element(const mjSpec& scene, const ElementSpec& element, const std::string& class_name,
                     const std::string& what) {
  SpecPtr copy(mj_copySpec(&scene));
  if (!copy) throw Error(what + ": MuJoCo could not copy the scene's spec");
  const auto kind = element_kind(element.tag);
  const bool in_body = kind && *kind != "actuator" && *kind != "sensor" && *kind != "default";
  mjsBody* parent =
      in_body ? mjs_findBody(copy.get(), element.parent.empty() ? "world" : element.parent.c_str())
              : nullptr;
  mjsDefault* def = class_name.empty()
                        ? (element.tag == "default" ? mjs_getSpecDefault(copy.get()) : nullptr)
                        : mjs_findDefault(copy.get(), class_name.c_str());
  make_element(*copy, element, parent, def, what);
  return copy;
}

}  // namespace mjarm::scene_detail
