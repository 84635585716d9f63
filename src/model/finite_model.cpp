#include "mjarm/model/finite_model.hpp"

#include <mujoco/mjxmacro.h>

#include <charconv>
#include <cmath>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"

namespace mjarm {

namespace {

// what an array's prefix belongs to: the MJCF element and the object type that names it
struct Owner {
  std::string_view prefix;
  std::string_view element;
  int type;  // mjtObj, or -1 when the row does not name an object directly
};
constexpr Owner kOwners[] = {
    {"body_", "body", mjOBJ_BODY},
    {"jnt_", "joint", mjOBJ_JOINT},
    {"dof_", "joint", -1},
    {"geom_", "geom", mjOBJ_GEOM},
    {"site_", "site", mjOBJ_SITE},
    {"cam_", "camera", mjOBJ_CAMERA},
    {"light_", "light", mjOBJ_LIGHT},
    {"mesh_", "mesh", -1},
    {"skin_", "skin", mjOBJ_SKIN},
    {"hfield_", "hfield", -1},
    {"mat_", "material", mjOBJ_MATERIAL},
    {"pair_", "pair", mjOBJ_PAIR},
    {"eq_", "equality", mjOBJ_EQUALITY},
    {"tendon_", "tendon", mjOBJ_TENDON},
    {"wrap_", "tendon", -1},
    {"actuator_", "actuator", mjOBJ_ACTUATOR},
    {"sensor_", "sensor", mjOBJ_SENSOR},
    {"numeric_", "numeric", -1},
    {"tuple_", "tuple", -1},
    {"key_", "key", mjOBJ_KEY},
    {"qpos", "joint", -1},
};

// arrays whose MJCF attribute has another name, or that come from a child element
struct Attribute {
  std::string_view array;
  std::string_view attribute;
};
constexpr Attribute kAttributes[] = {
    {"body_quat", "quat / euler / axisangle / xyaxes / zaxis"},
    {"body_ipos", "<inertial> pos"},
    {"body_iquat", "<inertial> quat"},
    {"body_mass", "<inertial> mass (or the mass of its geoms)"},
    {"body_inertia", "<inertial> diaginertia / fullinertia (or its geoms)"},
    {"geom_quat", "quat / euler / axisangle / xyaxes / zaxis / fromto"},
    {"site_quat", "quat / euler / axisangle / xyaxes / zaxis / fromto"},
    {"cam_quat", "quat / euler / axisangle / xyaxes / zaxis"},
    {"qpos0", "ref"},
    {"qpos_spring", "springref"},
    {"mesh_vert", "vertices (or its file)"},
    {"mesh_normal", "normals (or its file)"},
    {"tendon_solref_lim", "solreflimit"},
    {"tendon_solimp_lim", "solimplimit"},
    {"tendon_solref_fri", "solreffriction"},
    {"tendon_solimp_fri", "solimpfriction"},
};

// arrays the compiler derives from the others (bounding volumes among them); checked last
bool derived(std::string_view name) {
  if (name.starts_with("bvh_") || name.starts_with("oct_") || name == "dof_length" ||
      name == "efm0_L")
    return true;
  for (std::string_view suffix : {"qpos0", "subtreemass", "invweight0", "M0", "rbound", "aabb",
                                  "poscom0", "pos0", "mat0", "dir0", "vert0", "node0", "length0",
                                  "acc0", "lengthrange"}) {
    if (name.ends_with(suffix)) return true;
  }
  return false;
}

// arrays of lengths, masses and inertias given by the model: a value beyond mjMAXVAL there is
// one MuJoCo's own state checks call diverged ("Nan, Inf or huge value in QACC") at the first
// step, or turns into inf in the mass matrix
constexpr std::string_view kBoundedArrays[] = {
    "body_pos",  "body_ipos", "body_mass", "body_inertia", "jnt_pos",  "geom_pos",
    "geom_size", "site_pos",  "site_size", "cam_pos",      "light_pos", "key_qpos",
    "key_mpos",  "mesh_scale", "mesh_pos"};

bool bounded(std::string_view name) {
  for (std::string_view b : kBoundedArrays)
    if (b == name) return true;
  return false;
}

class FiniteCheck {
 public:
  FiniteCheck(const mjModel& m, std::string_view source) : m_(m), source_(source) {}

  void check_arrays(bool derived_pass) {
    const mjModel* m = &m_;
    MJMODEL_POINTERS_PREAMBLE(m)
#define X(type, name, nr, nc) check(#name, m->name, m->nr, nc, derived_pass);
    MJMODEL_POINTERS
#undef X
  }

  void check_options() {
    const mjOption& opt = m_.opt;
#define X(type, name, n) check_option("<option>", #name, "opt." #name, &opt.name, n);
#define XVEC(type, name, n) check_option("<option>", #name, "opt." #name, opt.name, n);
    MJOPTION_FIELDS
#undef XVEC
#undef X
  }

  // <statistic> and <visual>: a NaN there reaches the renderer's camera and clipping planes
  void check_statistic_and_visual() {
    const mjStatistic& stat = m_.stat;
#define X(name, n) check_option("<statistic>", #name, "stat." #name, &stat.name, n);
#define XVEC(name, n) check_option("<statistic>", #name, "stat." #name, stat.name, n);
    MJSTATISTIC_FIELDS
#undef XVEC
#undef X
    const mjVisual& vis = m_.vis;
    std::string group;  // the <visual> child element being checked
#define X(type, name, n) \
  check_option("<visual> <" + group + ">", #name, "vis." + group + "." #name, &section.name, n);
#define XVEC(type, name, n) \
  check_option("<visual> <" + group + ">", #name, "vis." + group + "." #name, section.name, n);
#define VISUAL(child, fields)          \
  {                                    \
    group = #child;                    \
    const auto& section = vis.child;   \
    fields                             \
  }
    VISUAL(global, MJVISUAL_GLOBAL_FIELDS)
    VISUAL(quality, MJVISUAL_QUALITY_FIELDS)
    VISUAL(headlight, MJVISUAL_HEADLIGHT_FIELDS)
    VISUAL(map, MJVISUAL_MAP_FIELDS)
    VISUAL(scale, MJVISUAL_SCALE_FIELDS)
    VISUAL(rgba, MJVISUAL_RGBA_FIELDS)
#undef VISUAL
#undef XVEC
#undef X
  }

  // lengths, masses and inertias up to mjMAXVAL (kMaxModelMagnitude)
  void check_magnitudes() {
    const mjModel* m = &m_;
    MJMODEL_POINTERS_PREAMBLE(m)
#define X(type, name, nr, nc) check_magnitude(#name, m->name, m->nr, nc);
    MJMODEL_POINTERS
#undef X
  }

 private:
  template <class T>
  void check(std::string_view name, const T* values, int rows, int cols, bool derived_pass) {
    if constexpr (std::is_same_v<T, mjtNum> || std::is_same_v<T, float>) {
      if (derived(name) != derived_pass || name.ends_with("_user") || cols <= 0) return;
      for (int r = 0; r < rows; ++r) {
        const T* row = values + static_cast<std::ptrdiff_t>(r) * cols;
        for (int c = 0; c < cols; ++c) {
          if (!std::isfinite(row[c])) fail(name, r, row, cols);
        }
      }
    }
  }

  template <class T>
  void check_magnitude(std::string_view name, const T* values, int rows, int cols) {
    if constexpr (std::is_same_v<T, mjtNum> || std::is_same_v<T, float>) {
      if (!bounded(name) || cols <= 0) return;
      for (int r = 0; r < rows; ++r) {
        const T* row = values + static_cast<std::ptrdiff_t>(r) * cols;
        for (int c = 0; c < cols; ++c) {
          if (std::abs(row[c]) > kMaxModelMagnitude)
            fail(name, r, row, cols,
                 "a value beyond " + number_text(kMaxModelMagnitude) +
                     " (MuJoCo's mjMAXVAL: its state checks call a larger value diverged)");
        }
      }
    }
  }

  // flags and enums: always finite
  void check_option(const std::string&, std::string_view, const std::string&, const int*, int) {}
  template <class T>
  void check_option(const std::string& element, std::string_view name, const std::string& field,
                    const T* values, int n) {
    for (int i = 0; i < n; ++i) {
      if (std::isfinite(values[i])) continue;
      throw Error("model " + std::string(source_) + " has a non-finite number: " +
                  element + " " + std::string(name) + " = " + format(values, n) + " (mjModel::" +
                  field + ")");
    }
  }

  template <class T>
  static std::string format(const T* values, int n) {
    std::string text;
    for (int i = 0; i < n && i < 12; ++i) text += (i ? " " : "") + value_text(values[i]);
    if (n > 12) text += " ...";
    return text;
  }

  // a float in its own shortest form (0.1f is "0.1", not the double 0.10000000149011612)
  static std::string value_text(float value) {
    if (!std::isfinite(value)) return number_text(value);
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
  }
  static std::string value_text(double value) { return number_text(value); }

  // "body 'link3'" (or "body 4" when unnamed) for row `row` of the array `name`
  std::string owner_of(std::string_view name, int row) const {
    for (const Owner& o : kOwners) {
      if (!name.starts_with(o.prefix)) continue;
      int type = o.type, id = row;
      if (o.prefix == "dof_") {
        type = mjOBJ_JOINT;
        id = m_.dof_jntid[row];
      } else if (o.prefix == "qpos") {
        // the joint whose coordinates hold this row
        type = mjOBJ_JOINT;
        for (int j = 0; j < m_.njnt; ++j) {
          if (m_.jnt_qposadr[j] <= row) id = j;
        }
      } else if (type < 0) {
        return std::string(o.element) + " data, row " + std::to_string(row);
      }
      const char* object = mj_id2name(&m_, type, id);
      return std::string(o.element) + (object != nullptr && *object != '\0'
                                           ? " '" + std::string(object) + "'"
                                           : " " + std::to_string(id) + " (unnamed)");
    }
    return "row " + std::to_string(row);
  }

  template <class T>
  [[noreturn]] void fail(std::string_view name, int row, const T* values, int cols,
                         const std::string& what = "a non-finite number") const {
    std::string attribute;
    for (const Attribute& a : kAttributes) {
      if (a.array == name) attribute = a.attribute;
    }
    if (attribute.empty()) attribute = std::string(name.substr(name.find('_') + 1));
    throw Error("model " + std::string(source_) + " has " + what + ": " + owner_of(name, row) +
                ", attribute " + attribute +
                " = " + format(values, cols) + " (mjModel::" + std::string(name) + ")");
  }

  const mjModel& m_;
  std::string_view source_;
};

}  // namespace

void check_model_finite(const mjModel& m, std::string_view source) {
  FiniteCheck check(m, source);
  // what the model gives first, then what the compiler derives from it (<statistic> among it)
  check.check_options();
  check.check_arrays(false);
  check.check_magnitudes();
  check.check_statistic_and_visual();
  check.check_arrays(true);
}

}  // namespace mjarm
