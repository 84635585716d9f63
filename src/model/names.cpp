#include "mjarm/model/names.hpp"

#include <algorithm>

#include "mjarm/error.hpp"

namespace mjarm {

const char* object_kind_name(mjtObj type) noexcept {
  switch (type) {
    case mjOBJ_BODY:
      return "body";
    case mjOBJ_JOINT:
      return "joint";
    case mjOBJ_GEOM:
      return "geom";
    case mjOBJ_SITE:
      return "site";
    case mjOBJ_CAMERA:
      return "camera";
    case mjOBJ_LIGHT:
      return "light";
    case mjOBJ_MESH:
      return "mesh";
    case mjOBJ_ACTUATOR:
      return "actuator";
    case mjOBJ_SENSOR:
      return "sensor";
    case mjOBJ_KEY:
      return "keyframe";
    case mjOBJ_TENDON:
      return "tendon";
    case mjOBJ_EQUALITY:
      return "equality";
    default:
      return "object";
  }
}

std::vector<std::string> object_names(const mjModel& m, mjtObj type) {
  std::vector<std::string> names;
  for (int id = 0;; ++id) {
    const char* name = mj_id2name(&m, type, id);
    if (name == nullptr) {
      // mj_id2name gives null both past the end and for unnamed objects: stop at the count
      int count = 0;
      switch (type) {
        case mjOBJ_BODY:
          count = m.nbody;
          break;
        case mjOBJ_JOINT:
          count = m.njnt;
          break;
        case mjOBJ_GEOM:
          count = m.ngeom;
          break;
        case mjOBJ_SITE:
          count = m.nsite;
          break;
        case mjOBJ_CAMERA:
          count = m.ncam;
          break;
        case mjOBJ_LIGHT:
          count = m.nlight;
          break;
        case mjOBJ_MESH:
          count = m.nmesh;
          break;
        case mjOBJ_ACTUATOR:
          count = m.nu;
          break;
        case mjOBJ_SENSOR:
          count = m.nsensor;
          break;
        case mjOBJ_KEY:
          count = m.nkey;
          break;
        case mjOBJ_TENDON:
          count = m.ntendon;
          break;
        case mjOBJ_EQUALITY:
          count = m.neq;
          break;
        default:
          count = 0;
      }
      if (id >= count) break;
      names.emplace_back();
      continue;
    }
    names.emplace_back(name);
  }
  return names;
}

std::string model_name(const mjModel& m) {
  // the model name is stored at the start of the names buffer
  return m.nnames > 0 && m.names[0] != '\0' ? std::string(m.names) : std::string("unnamed");
}

int try_find_object(const mjModel& m, mjtObj type, std::string_view name) noexcept {
  const std::string key(name);
  return mj_name2id(&m, type, key.c_str());
}

int find_object(const mjModel& m, mjtObj type, std::string_view name) {
  const int id = try_find_object(m, type, name);
  if (id >= 0) return id;
  const auto names = object_names(m, type);
  std::string message = std::string(object_kind_name(type)) + " '" + std::string(name) +
                        "' not found in model '" + model_name(m) + "'";
  const auto close = closest_names(name, names, 5);
  if (close.empty()) {
    message += "; it has no named " + std::string(object_kind_name(type)) + "s";
  } else {
    message += "; closest: ";
    for (std::size_t i = 0; i < close.size(); ++i) message += (i ? ", " : "") + close[i];
  }
  throw Error(message);
}

}  // namespace mjarm
