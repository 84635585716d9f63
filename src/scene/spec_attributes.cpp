#include "spec_attributes.hpp"

#include <mujoco/mjspecmacro.h>
#include <mujoco/mjxmacro.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "frame_check.hpp"
#include "mjarm/error.hpp"
#include "mjarm/number_text.hpp"
#include "mjarm/model/names.hpp"

namespace mjarm::scene_detail {

namespace {

enum class FieldKind { none, real, real32, integer, byte, boolean, keyword, text };

struct Keyword {
  std::string_view name;
  int value;
};

/// One field of an mjs struct (or of mjOption) at its byte offset.
struct Field {
  std::string_view name;  ///< the struct's field name
  FieldKind kind = FieldKind::none;
  int count = 1;
  std::size_t offset = 0;
  std::span<const Keyword> keywords;  ///< for FieldKind::keyword
};

// MJCF keywords of the enumerations an edit may want to change
constexpr Keyword kGeomTypes[] = {
    {"plane", mjGEOM_PLANE},         {"hfield", mjGEOM_HFIELD},     {"sphere", mjGEOM_SPHERE},
    {"capsule", mjGEOM_CAPSULE},     {"ellipsoid", mjGEOM_ELLIPSOID}, {"cylinder", mjGEOM_CYLINDER},
    {"box", mjGEOM_BOX},             {"mesh", mjGEOM_MESH},         {"sdf", mjGEOM_SDF}};
constexpr Keyword kJointTypes[] = {
    {"free", mjJNT_FREE}, {"ball", mjJNT_BALL}, {"slide", mjJNT_SLIDE}, {"hinge", mjJNT_HINGE}};
constexpr Keyword kLimited[] = {
    {"false", mjLIMITED_FALSE}, {"true", mjLIMITED_TRUE}, {"auto", mjLIMITED_AUTO}};
constexpr Keyword kAlignFree[] = {
    {"false", mjALIGNFREE_FALSE}, {"true", mjALIGNFREE_TRUE}, {"auto", mjALIGNFREE_AUTO}};
constexpr Keyword kCamLight[] = {{"fixed", mjCAMLIGHT_FIXED},
                                 {"track", mjCAMLIGHT_TRACK},
                                 {"trackcom", mjCAMLIGHT_TRACKCOM},
                                 {"targetbody", mjCAMLIGHT_TARGETBODY},
                                 {"targetbodycom", mjCAMLIGHT_TARGETBODYCOM}};
constexpr Keyword kLightTypes[] = {{"spot", mjLIGHT_SPOT},
                                   {"directional", mjLIGHT_DIRECTIONAL},
                                   {"point", mjLIGHT_POINT},
                                   {"image", mjLIGHT_IMAGE}};
constexpr Keyword kProjections[] = {{"perspective", mjPROJ_PERSPECTIVE},
                                    {"orthographic", mjPROJ_ORTHOGRAPHIC}};
constexpr Keyword kGainTypes[] = {{"fixed", mjGAIN_FIXED},
                                  {"affine", mjGAIN_AFFINE},
                                  {"muscle", mjGAIN_MUSCLE},
                                  {"user", mjGAIN_USER}};
constexpr Keyword kBiasTypes[] = {{"none", mjBIAS_NONE},
                                  {"affine", mjBIAS_AFFINE},
                                  {"muscle", mjBIAS_MUSCLE},
                                  {"user", mjBIAS_USER}};
constexpr Keyword kDynTypes[] = {{"none", mjDYN_NONE},     {"integrator", mjDYN_INTEGRATOR},
                                 {"filter", mjDYN_FILTER}, {"filterexact", mjDYN_FILTEREXACT},
                                 {"muscle", mjDYN_MUSCLE}, {"user", mjDYN_USER}};
constexpr Keyword kBuiltins[] = {{"none", mjBUILTIN_NONE},
                                 {"gradient", mjBUILTIN_GRADIENT},
                                 {"checker", mjBUILTIN_CHECKER},
                                 {"flat", mjBUILTIN_FLAT}};
constexpr Keyword kMarks[] = {{"none", mjMARK_NONE},
                              {"edge", mjMARK_EDGE},
                              {"cross", mjMARK_CROSS},
                              {"random", mjMARK_RANDOM}};
constexpr Keyword kIntegrators[] = {{"Euler", mjINT_EULER},
                                    {"RK4", mjINT_RK4},
                                    {"implicit", mjINT_IMPLICIT},
                                    {"implicitfast", mjINT_IMPLICITFAST}};
constexpr Keyword kCones[] = {{"pyramidal", mjCONE_PYRAMIDAL}, {"elliptic", mjCONE_ELLIPTIC}};
constexpr Keyword kJacobians[] = {
    {"dense", mjJAC_DENSE}, {"sparse", mjJAC_SPARSE}, {"auto", mjJAC_AUTO}};
constexpr Keyword kSolvers[] = {{"PGS", mjSOL_PGS}, {"CG", mjSOL_CG}, {"Newton", mjSOL_NEWTON}};

template <class T>
std::span<const Keyword> keywords_of() {
  if constexpr (std::is_same_v<T, mjtGeom>) return kGeomTypes;
  if constexpr (std::is_same_v<T, mjtJoint>) return kJointTypes;
  if constexpr (std::is_same_v<T, mjtLimited>) return kLimited;
  if constexpr (std::is_same_v<T, mjtAlignFree>) return kAlignFree;
  if constexpr (std::is_same_v<T, mjtCamLight>) return kCamLight;
  if constexpr (std::is_same_v<T, mjtLightType>) return kLightTypes;
  if constexpr (std::is_same_v<T, mjtProjection>) return kProjections;
  if constexpr (std::is_same_v<T, mjtGain>) return kGainTypes;
  if constexpr (std::is_same_v<T, mjtBias>) return kBiasTypes;
  if constexpr (std::is_same_v<T, mjtDyn>) return kDynTypes;
  if constexpr (std::is_same_v<T, mjtBuiltin>) return kBuiltins;
  if constexpr (std::is_same_v<T, mjtMark>) return kMarks;
  return {};
}

template <class T>
Field make_field(std::string_view name, std::size_t offset, int count) {
  Field f{name, FieldKind::none, count, offset, {}};
  if constexpr (std::is_same_v<T, double>) {
    f.kind = FieldKind::real;
  } else if constexpr (std::is_same_v<T, float>) {
    f.kind = FieldKind::real32;
  } else if constexpr (std::is_same_v<T, int>) {
    f.kind = FieldKind::integer;
  } else if constexpr (std::is_same_v<T, mjtByte>) {
    f.kind = FieldKind::byte;
  } else if constexpr (std::is_same_v<T, bool>) {
    f.kind = FieldKind::boolean;
  } else if constexpr (std::is_same_v<T, mjString*>) {
    f.kind = FieldKind::text;
  } else if constexpr (std::is_enum_v<T>) {
    static_assert(sizeof(T) == sizeof(int), "enumerations are read and written as int");
    f.keywords = keywords_of<T>();
    if (!f.keywords.empty()) f.kind = FieldKind::keyword;
  }
  return f;
}

// every field of an mjs struct (or mjOption), from MuJoCo's own list of them
#define X(T, name, n) make_field<T>(#name, offsetof(Struct, name), n),
#define XVEC X
#define MJARM_FIELDS_OF(S, LIST)     \
  [] {                               \
    using Struct = S;                \
    return std::vector<Field>{LIST}; \
  }()

std::vector<Field> option_fields() {
  std::vector<Field> fields = MJARM_FIELDS_OF(mjOption, MJOPTION_FIELDS);
  for (Field& f : fields) {
    // integers in mjOption, keywords in MJCF
    const std::pair<std::string_view, std::span<const Keyword>> named[] = {
        {"integrator", kIntegrators},
        {"cone", kCones},
        {"jacobian", kJacobians},
        {"solver", kSolvers}};
    for (const auto& [name, keywords] : named) {
      if (f.name != name) continue;
      f.kind = FieldKind::keyword;
      f.keywords = keywords;
    }
    // bit masks, written as <flag> elements and group lists in MJCF
    if (f.name == "disableflags" || f.name == "enableflags" || f.name == "disableactuator")
      f.kind = FieldKind::none;
  }
  return fields;
}

using Aliases = std::vector<std::pair<std::string_view, std::string_view>>;  // MJCF -> field

// MJCF names of the limit and friction solver parameters and of actuator force limits
const Aliases kLimitAliases = {
    {"solreflimit", "solref_limit"},       {"solimplimit", "solimp_limit"},
    {"solreffriction", "solref_friction"}, {"solimpfriction", "solimp_friction"},
    {"actuatorfrcrange", "actfrcrange"},   {"actuatorfrclimited", "actfrclimited"},
    {"actuatorgravcomp", "actgravcomp"}};

/// An element type a scene edits: its struct's fields and the MJCF names that differ from them.
struct ElementType {
  mjtObj type;
  std::vector<Field> fields;
  Aliases aliases;
  void* (*as_struct)(mjsElement*);
};

template <class S, S* (*As)(mjsElement*)>
void* struct_of(mjsElement* e) {
  return As(e);
}

const ElementType* element_type(mjtObj type) {
  static const ElementType kTypes[] = {
      {mjOBJ_BODY, MJARM_FIELDS_OF(mjsBody, MJSBODY_FIELDS), {}, struct_of<mjsBody, mjs_asBody>},
      {mjOBJ_FRAME, MJARM_FIELDS_OF(mjsFrame, MJSFRAME_FIELDS), {},
       struct_of<mjsFrame, mjs_asFrame>},
      {mjOBJ_JOINT, MJARM_FIELDS_OF(mjsJoint, MJSJOINT_FIELDS), kLimitAliases,
       struct_of<mjsJoint, mjs_asJoint>},
      {mjOBJ_GEOM, MJARM_FIELDS_OF(mjsGeom, MJSGEOM_FIELDS),
       {{"mesh", "meshname"}, {"hfield", "hfieldname"}, {"fluidcoef", "fluid_coefs"}},
       struct_of<mjsGeom, mjs_asGeom>},
      {mjOBJ_SITE, MJARM_FIELDS_OF(mjsSite, MJSSITE_FIELDS), {{"mesh", "meshname"}},
       struct_of<mjsSite, mjs_asSite>},
      {mjOBJ_CAMERA, MJARM_FIELDS_OF(mjsCamera, MJSCAMERA_FIELDS),
       {{"target", "targetbody"},
        {"projection", "proj"},
        {"sensorsize", "sensor_size"},
        {"focal", "focal_length"},
        {"focalpixel", "focal_pixel"},
        {"principal", "principal_length"},
        {"principalpixel", "principal_pixel"}},
       struct_of<mjsCamera, mjs_asCamera>},
      {mjOBJ_LIGHT, MJARM_FIELDS_OF(mjsLight, MJSLIGHT_FIELDS), {{"target", "targetbody"}},
       struct_of<mjsLight, mjs_asLight>},
      {mjOBJ_ACTUATOR, MJARM_FIELDS_OF(mjsActuator, MJSACTUATOR_FIELDS), {},
       struct_of<mjsActuator, mjs_asActuator>},
      {mjOBJ_SENSOR, MJARM_FIELDS_OF(mjsSensor, MJSSENSOR_FIELDS), {},
       struct_of<mjsSensor, mjs_asSensor>},
      {mjOBJ_TENDON, MJARM_FIELDS_OF(mjsTendon, MJSTENDON_FIELDS), kLimitAliases,
       struct_of<mjsTendon, mjs_asTendon>},
      {mjOBJ_EQUALITY, MJARM_FIELDS_OF(mjsEquality, MJSEQUALITY_FIELDS), {},
       struct_of<mjsEquality, mjs_asEquality>},
      {mjOBJ_PAIR, MJARM_FIELDS_OF(mjsPair, MJSPAIR_FIELDS),
       {{"geom1", "geomname1"}, {"geom2", "geomname2"}}, struct_of<mjsPair, mjs_asPair>},
      {mjOBJ_MESH, MJARM_FIELDS_OF(mjsMesh, MJSMESH_FIELDS), {}, struct_of<mjsMesh, mjs_asMesh>},
      {mjOBJ_HFIELD, MJARM_FIELDS_OF(mjsHField, MJSHFIELD_FIELDS), {},
       struct_of<mjsHField, mjs_asHField>},
      {mjOBJ_MATERIAL, MJARM_FIELDS_OF(mjsMaterial, MJSMATERIAL_FIELDS), {},
       struct_of<mjsMaterial, mjs_asMaterial>},
      {mjOBJ_TEXTURE, MJARM_FIELDS_OF(mjsTexture, MJSTEXTURE_FIELDS), {},
       struct_of<mjsTexture, mjs_asTexture>}};
  for (const ElementType& t : kTypes)
    if (t.type == type) return &t;
  return nullptr;
}

#undef MJARM_FIELDS_OF
#undef XVEC
#undef X

// orientation attributes: the quat field, or one of the alternatives in the `alt` struct
struct Orientation {
  std::string_view name;
  mjtOrientation type;
  std::size_t offset;  // in mjsOrientation; unused for quat
  int count;
};
constexpr Orientation kOrientations[] = {
    {"quat", mjORIENTATION_QUAT, 0, 4},
    {"axisangle", mjORIENTATION_AXISANGLE, offsetof(mjsOrientation, axisangle), 4},
    {"xyaxes", mjORIENTATION_XYAXES, offsetof(mjsOrientation, xyaxes), 6},
    {"zaxis", mjORIENTATION_ZAXIS, offsetof(mjsOrientation, zaxis), 3},
    {"euler", mjORIENTATION_EULER, offsetof(mjsOrientation, euler), 3}};

// fields MJCF lets a value list shorter than the field: the rest keep their values
bool takes_leading_values(std::string_view field) {
  static constexpr std::string_view kLeading[] = {
      "size",   "friction",        "gainprm", "biasprm",   "dynprm",      "solimp",
      "solimp_limit", "solimp_friction", "gear", "data", "stiffness", "damping",
      "fluid_coefs",  "intprm",    "o_solimp", "o_friction"};
  return std::find(std::begin(kLeading), std::end(kLeading), field) != std::end(kLeading);
}

const Field* find_field(std::span<const Field> fields, std::string_view name) {
  for (const Field& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

/// The MJCF names of the attributes a table can read and write.
std::vector<std::string> attribute_names(const ElementType& table) {
  std::vector<std::string> names;
  const bool oriented = find_field(table.fields, "alt") != nullptr;
  for (const Field& f : table.fields) {
    if (f.kind == FieldKind::none) continue;
    std::string_view name = f.name;
    for (const auto& [mjcf, field] : table.aliases)
      if (field == f.name) name = mjcf;
    if (oriented && f.name == "quat") continue;
    names.emplace_back(name);
  }
  if (oriented)
    for (const Orientation& o : kOrientations) names.emplace_back(o.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::string comma_list(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

[[noreturn]] void unknown_attribute(const std::string& what, std::string_view attribute,
                                    const std::vector<std::string>& known) {
  std::string message = what + ": no attribute '" + std::string(attribute) + "'";
  const auto close = closest_names(attribute, known, 3);
  if (!close.empty()) message += "; closest: " + comma_list(close);
  throw Error(message + " (attributes that can be read and set: " + comma_list(known) + ")");
}

template <class T>
void append_number(std::string& out, T value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (!out.empty()) out += ' ';
  out.append(buffer, result.ptr);
}

std::string keyword_list(std::span<const Keyword> keywords) {
  std::string out;
  for (const Keyword& k : keywords) out += (out.empty() ? "" : ", ") + std::string(k.name);
  return out;
}

/// The value of field @p f at @p base as text; nullopt for an unset value.
std::optional<std::string> format_field(const Field& f, const std::byte* base) {
  const std::byte* at = base + f.offset;
  std::string out;
  for (int i = 0; i < f.count; ++i) {
    switch (f.kind) {
      case FieldKind::real: {
        const double v = reinterpret_cast<const double*>(at)[i];
        if (std::isnan(v)) return std::nullopt;  // MuJoCo's mark of an unset number
        append_number(out, v);
        break;
      }
      case FieldKind::real32: {
        const float v = reinterpret_cast<const float*>(at)[i];
        if (std::isnan(v)) return std::nullopt;
        append_number(out, v);
        break;
      }
      case FieldKind::integer:
        append_number(out, reinterpret_cast<const int*>(at)[i]);
        break;
      case FieldKind::byte:
        append_number(out, static_cast<int>(reinterpret_cast<const mjtByte*>(at)[i]));
        break;
      case FieldKind::boolean:
        out += std::string(out.empty() ? "" : " ") +
               (reinterpret_cast<const bool*>(at)[i] ? "true" : "false");
        break;
      case FieldKind::keyword: {
        const int v = reinterpret_cast<const int*>(at)[i];
        const auto k = std::find_if(f.keywords.begin(), f.keywords.end(),
                                    [&](const Keyword& w) { return w.value == v; });
        if (k == f.keywords.end()) {
          append_number(out, v);
        } else {
          out += std::string(out.empty() ? "" : " ") + std::string(k->name);
        }
        break;
      }
      case FieldKind::text: {
        const std::string* s = *reinterpret_cast<mjString* const*>(at);
        if (s == nullptr || s->empty()) return std::nullopt;
        return *s;
      }
      case FieldKind::none:
        return std::nullopt;
    }
  }
  return out;
}

/// A value to write: text, or numbers already parsed.
struct Input {
  std::string_view text;
  std::span<const double> numbers;
  bool is_text = true;
};

std::vector<double> numbers_of(const Input& in, const std::string& what,
                               std::string_view attribute) {
  if (!in.is_text) return {in.numbers.begin(), in.numbers.end()};
  std::vector<double> values;
  const char* p = in.text.data();
  const char* end = p + in.text.size();
  while (true) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r' || *p == ',')) ++p;
    if (p == end) break;
    double v = 0.0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() || (next < end && *next != ' ' && *next != '\t' && *next != '\n' &&
                              *next != '\r' && *next != ',')) {
      throw Error(what + ": " + std::string(attribute) + " expects numbers, got '" +
                  std::string(in.text) + "'");
    }
    values.push_back(v);
    p = next;
  }
  return values;
}

void check_count(std::size_t given, const Field& f, bool leading, const std::string& what,
                 std::string_view attribute) {
  const auto count = static_cast<std::size_t>(f.count);
  if (given == count || (leading && given >= 1 && given <= count)) return;
  throw Error(what + ": " + std::string(attribute) + " expects " +
              (leading && count > 1 ? "1 to " : "") + std::to_string(count) + " number" +
              (count > 1 ? "s" : "") + ", got " + std::to_string(given));
}

/// Checks every value first: a refused value leaves the field as it was.
void write_numbers(const Field& f, std::byte* base, std::span<const double> v,
                   const std::string& what, std::string_view attribute) {
  const bool whole = f.kind == FieldKind::integer || f.kind == FieldKind::byte;
  const double top = f.kind == FieldKind::byte     ? 255.0
                     : f.kind == FieldKind::integer ? double(std::numeric_limits<int>::max())
                     : f.kind == FieldKind::real32  ? double(std::numeric_limits<float>::max())
                                                    : std::numeric_limits<double>::max();
  const double bottom = f.kind == FieldKind::byte ? 0.0 : -top;
  for (double x : v) {
    if (!std::isfinite(x))
      throw Error(what + ": " + std::string(attribute) + " must be finite numbers");
    if ((whole && x != std::floor(x)) || x < bottom || x > top)
      throw Error(what + ": " + std::string(attribute) + " expects " +
                  (whole ? "whole numbers" : "numbers") + " in [" + number_text(bottom) + ", " +
                  number_text(top) + "], got " + number_text(x));
  }
  std::byte* at = base + f.offset;
  for (std::size_t i = 0; i < v.size(); ++i) {
    switch (f.kind) {
      case FieldKind::real:
        reinterpret_cast<double*>(at)[i] = v[i];
        break;
      case FieldKind::real32:
        reinterpret_cast<float*>(at)[i] = static_cast<float>(v[i]);
        break;
      case FieldKind::integer:
        reinterpret_cast<int*>(at)[i] = static_cast<int>(v[i]);
        break;
      case FieldKind::byte:
        reinterpret_cast<mjtByte*>(at)[i] = static_cast<mjtByte>(v[i]);
        break;
      default:
        break;
    }
  }
}

/// Writes @p in into field @p f of the struct at @p base.
void write_field(const Field& f, std::byte* base, const Input& in, const std::string& what,
                 std::string_view attribute) {
  switch (f.kind) {
    case FieldKind::text: {
      if (!in.is_text)
        throw Error(what + ": " + std::string(attribute) + " expects a name, got numbers");
      mjs_setString(*reinterpret_cast<mjString**>(base + f.offset), std::string(in.text).c_str());
      return;
    }
    case FieldKind::boolean:
    case FieldKind::keyword: {
      const std::span<const Keyword> keywords = f.kind == FieldKind::boolean
                                                    ? std::span<const Keyword>(kLimited).first(2)
                                                    : f.keywords;
      const auto k = std::find_if(keywords.begin(), keywords.end(), [&](const Keyword& w) {
        return in.is_text && w.name == in.text;
      });
      if (k == keywords.end()) {
        throw Error(what + ": " + std::string(attribute) + " expects one of " +
                    keyword_list(keywords) + ", got " +
                    (in.is_text ? "'" + std::string(in.text) + "'" : std::string("numbers")));
      }
      if (f.kind == FieldKind::boolean) {
        *reinterpret_cast<bool*>(base + f.offset) = k->value != 0;
      } else {
        *reinterpret_cast<int*>(base + f.offset) = k->value;
      }
      return;
    }
    case FieldKind::real:
    case FieldKind::real32:
    case FieldKind::integer:
    case FieldKind::byte: {
      const std::vector<double> v = numbers_of(in, what, attribute);
      check_count(v.size(), f, takes_leading_values(f.name), what, attribute);
      write_numbers(f, base, v, what, attribute);
      return;
    }
    case FieldKind::none:
      break;
  }
  throw Error(what + ": " + std::string(attribute) + " cannot be set by name");
}

/// The field attribute @p attribute names in @p table (aliases resolved), or null.
const Field* field_for(const ElementType& table, std::string_view attribute) {
  std::string_view name = attribute;
  for (const auto& [mjcf, field] : table.aliases)
    if (mjcf == attribute) name = field;
  const Field* f = find_field(table.fields, name);
  return f != nullptr && f->kind != FieldKind::none ? f : nullptr;
}

const ElementType& require_type(const mjsElement& element, const std::string& what) {
  const ElementType* type = element_type(element.elemtype);
  if (type == nullptr) throw Error(what + ": its attributes cannot be read or set by name");
  return *type;
}

void write(mjsElement& element, std::string_view attribute, const Input& in,
           const std::string& what) {
  if (attribute == "class" || attribute == "childclass")
    throw Error(what + ": a default class applies when an element is made; set the attributes "
                       "themselves instead of '" + std::string(attribute) + "'");
  const ElementType& table = require_type(element, what);
  auto* base = static_cast<std::byte*>(table.as_struct(&element));
  if (const Field* alt = find_field(table.fields, "alt")) {
    for (const Orientation& o : kOrientations) {
      if (o.name != attribute) continue;
      const std::vector<double> v = numbers_of(in, what, attribute);
      if (v.size() != static_cast<std::size_t>(o.count))
        throw Error(what + ": " + std::string(attribute) + " expects " + std::to_string(o.count) +
                    " numbers, got " + std::to_string(v.size()));
      // MuJoCo would keep a zero quat as it is and refuse a zero axis naming no attribute
      check_orientation(o.name, v, what);
      const Field values{o.name, FieldKind::real, o.count,
                         o.type == mjORIENTATION_QUAT ? find_field(table.fields, "quat")->offset
                                                      : alt->offset + o.offset,
                         {}};
      write_numbers(values, base, v, what, attribute);
      reinterpret_cast<mjsOrientation*>(base + alt->offset)->type = o.type;
      return;
    }
  }
  const Field* f = field_for(table, attribute);
  if (f == nullptr) unknown_attribute(what, attribute, attribute_names(table));
  write_field(*f, base, in, what, attribute);
}

const std::vector<Field>& options() {
  static const std::vector<Field> fields = option_fields();
  return fields;
}

const Field& option_field(std::string_view attribute) {
  const Field* f = find_field(options(), attribute);
  if (f != nullptr && f->kind != FieldKind::none) return *f;
  std::vector<std::string> known;
  for (const Field& g : options())
    if (g.kind != FieldKind::none) known.emplace_back(g.name);
  unknown_attribute("option", attribute, known);
}

}  // namespace

std::optional<std::string> read_attribute(mjsElement& element, std::string_view attribute,
                                          const std::string& what) {
  const ElementType& table = require_type(element, what);
  const auto* base = static_cast<const std::byte*>(table.as_struct(&element));
  if (const Field* alt = find_field(table.fields, "alt")) {
    const auto& orientation = *reinterpret_cast<const mjsOrientation*>(base + alt->offset);
    for (const Orientation& o : kOrientations) {
      if (o.name != attribute) continue;
      // only the orientation the element is given by
      if (orientation.type != o.type) return std::nullopt;
      const Field values{o.name, FieldKind::real, o.count,
                         o.type == mjORIENTATION_QUAT ? find_field(table.fields, "quat")->offset
                                                      : alt->offset + o.offset,
                         {}};
      return format_field(values, base);
    }
  }
  const Field* f = field_for(table, attribute);
  if (f == nullptr) unknown_attribute(what, attribute, attribute_names(table));
  return format_field(*f, base);
}

void write_attribute(mjsElement& element, std::string_view attribute, std::string_view text,
                     const std::string& what) {
  write(element, attribute, Input{text, {}, true}, what);
}

void write_attribute(mjsElement& element, std::string_view attribute,
                     std::span<const double> values, const std::string& what) {
  write(element, attribute, Input{{}, values, false}, what);
}

void write_option(mjOption& option, std::string_view attribute, std::string_view text) {
  const Field& f = option_field(attribute);
  write_field(f, reinterpret_cast<std::byte*>(&option), Input{text, {}, true}, "option",
              attribute);
}

void copy_option(const mjOption& from, mjOption& to, std::string_view attribute) {
  const Field& f = option_field(attribute);
  const std::size_t size = f.kind == FieldKind::real ? sizeof(double) : sizeof(int);
  std::memcpy(reinterpret_cast<std::byte*>(&to) + f.offset,
              reinterpret_cast<const std::byte*>(&from) + f.offset, size * f.count);
}

}  // namespace mjarm::scene_detail
