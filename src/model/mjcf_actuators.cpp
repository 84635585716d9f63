// Actuators: MuJoCo 3.x shortcut semantics (position kv / dampratio / timeconst / inheritrange,
// parameters kept from the class default) rewritten as explicit 2.2.2 <general> actuators.
//
// Both versions fold every actuator element of a default class into one per-class record, then
// start each actuator from its class's record. We evaluate every element twice, with the 3.x
// rules (what the model means) and the 2.2.2 rules (what 2.2.2 would build from the unchanged
// element); wherever they differ, the element is rewritten as a <general> that spells out the 3.x
// result, so 2.2.2 has nothing left to interpret.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mjcf_actuator_record.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace {

// placeholder tag of actuator defaults folded into another element
constexpr const char* kRemoved = "mjarm-removed";

// attributes that only feed the record; everything else on an actuator passes through
bool is_record_attr(std::string_view a) {
  return a == "kp" || a == "kv" || a == "dampratio" || a == "timeconst" || a == "inheritrange" ||
         a == "area" || a == "diameter" || a == "bias" || a == "gain" || a == "dyntype" ||
         a == "gaintype" || a == "biastype" || a == "dynprm" || a == "gainprm" || a == "biasprm";
}

// an element spelling out record `r` as a 2.2.2 <general>, keeping pass-through attributes
void write_general(XmlNode& e, const ActuatorRecord& r, double timestep) {
  std::vector<std::pair<std::string, std::string>> kept;
  for (auto& kv : e.attrs) {
    if (!is_record_attr(kv.first)) kept.push_back(std::move(kv));
  }
  e.attrs = std::move(kept);
  e.tag = "general";
  std::array<double, kNumPrm> dynprm = r.dynprm;
  std::string dyntype = r.dyntype;
  if (dyntype == "filterexact") {
    // the exact first-order update a' = u + (a-u)exp(-h/tau) equals 2.2.2's Euler filter
    // a' = a + h(u-a)/tau' for tau' = h / (1 - exp(-h/tau))
    dyntype = "filter";
    dynprm[0] = timestep / (1.0 - std::exp(-timestep / r.dynprm[0]));
  }
  e.set("dyntype", dyntype);
  e.set("gaintype", r.gaintype);
  e.set("biastype", r.biastype);
  // all entries: fewer would leave the rest to the class default
  e.set("dynprm", format_numbers(dynprm));
  e.set("gainprm", format_numbers(r.gainprm));
  e.set("biasprm", format_numbers(r.biasprm));
  if (r.force_ctrllimited && !e.has("ctrllimited")) e.set("ctrllimited", "true");
  if (r.force_actlimited && !e.has("actlimited")) e.set("actlimited", "true");
}

std::string reasons(const XmlNode& e, bool differs) {
  std::string s;
  for (const char* a : {"kv", "dampratio", "timeconst", "inheritrange"}) {
    if (const std::string* v = e.find(a)) {
      s += std::string(s.empty() ? "" : ", ") + a + "=\"" + *v + "\"";
    }
  }
  if (differs) {
    s += std::string(s.empty() ? "" : "; ") +
         "MuJoCo 3.x keeps parameters from the class default that 2.2.2 resets";
  }
  return s;
}

void index_joints(const XmlNode& body, const std::string& cc,
                  std::map<std::string, TargetIndex::Entry>& out) {
  const std::string* own = body.tag == "body" ? body.find("childclass") : nullptr;
  const std::string childclass = own ? *own : cc;
  for (const auto& c : body.children) {
    if (c.tag == "joint") {
      if (const std::string* name = c.find("name")) {
        const std::string* cls = c.find("class");
        out[*name] = {&c, cls ? *cls : (childclass.empty() ? std::string("main") : childclass)};
      }
    } else if (c.tag == "body") {
      index_joints(c, childclass, out);
    }
  }
}

// ctrlrange (or actrange) = centre of the target range +- inheritrange * half width
std::array<double, 2> inherited_range(const XmlNode& act, double inheritrange,
                                      const TargetIndex& targets, const Defaults& defaults,
                                      const Context& ctx) {
  const XmlNode* node = nullptr;
  std::string cls, kind;
  for (const char* key : {"joint", "jointinparent", "tendon"}) {
    const std::string* name = act.find(key);
    if (!name) continue;
    const auto& map = std::string_view(key) == "tendon" ? targets.tendons : targets.joints;
    const auto it = map.find(*name);
    if (it == map.end()) fail(act, std::string(key) + " '" + *name + "' not found");
    node = it->second.node;
    cls = it->second.cls;
    kind = std::string(default_kind(node->tag));
  }
  if (!node) fail(act, "inheritrange needs a joint or tendon transmission");
  const std::string* own = node->find("range");
  const auto range_text =
      own ? std::optional<std::string>(*own) : defaults.lookup(cls, kind, "range");
  if (!range_text) fail(act, "inheritrange: its target " + label(*node) + " has no range");
  const std::vector<double> r = parse_numbers(*node, "range", *range_text);
  if (r.size() != 2 || !(r[0] < r[1])) fail(*node, "range must be two increasing numbers");
  double scale = 1.0;
  if (kind == "joint") {
    const std::string* t = node->find("type");
    const std::string type = t ? *t : defaults.lookup(cls, "joint", "type").value_or("hinge");
    if (type == "ball" || type == "free") fail(act, "inheritrange on a " + type + " joint");
    // hinge ranges are compiled to radians, and the control lives in radians
    if (type == "hinge" && ctx.degrees) scale = std::numbers::pi / 180.0;
  }
  const double centre = 0.5 * (r[0] + r[1]) * scale;
  const double half = 0.5 * (r[1] - r[0]) * scale * inheritrange;
  return {centre - half, centre + half};
}

// an actuator range given on the element or by its class (3.x counts "0 0" as not given)
bool has_range(const XmlNode& e, const std::string& cls, const char* key,
               const Defaults& defaults) {
  const std::string* own = e.find(key);
  const auto text = own ? std::optional<std::string>(*own) : defaults.lookup(cls, "actuator", key);
  if (!text) return false;
  const std::vector<double> r = parse_numbers(e, key, *text);
  return std::any_of(r.begin(), r.end(), [](double x) { return x != 0; });
}

// MuJoCo 3.x inheritrange, by its two rules (xml_native_reader.cc and mjCActuator::Compile):
// the reader refuses ctrlrange (actrange) next to inheritrange on <position> (<intvelocity>)
// only; the compiler then sets the range of every actuator whose gain and bias make it a
// position servo (fixed gain, affine bias, gainprm[0] = -biasprm[1]) — ctrlrange for dyntype
// none / filterexact, actrange for integrator — and ignores inheritrange on any other actuator.
// A <general> gets inheritrange only from its class. Returns the note for the warning.
std::string apply_inheritrange(XmlNode& e, const ActuatorRecord& r, const std::string& cls,
                               const TargetIndex& targets, const Defaults& defaults,
                               const Context& ctx) {
  if (e.tag == "position" || e.tag == "intvelocity") {
    const char* key = e.tag == "intvelocity" ? "actrange" : "ctrlrange";
    if (has_range(e, cls, key, defaults)) {
      fail(e, std::string(key) + " and inheritrange cannot both be defined on <" + e.tag + ">");
    }
  }
  const bool servo =
      r.gaintype == "fixed" && r.biastype == "affine" && r.gainprm[0] == -r.biasprm[1];
  if (!servo) {
    return "; inheritrange=\"" + format_numbers(std::array<double, 1>{r.inheritrange}) +
           "\" from class '" + cls +
           "' ignored, as in MuJoCo 3.x: this actuator is not a position servo";
  }
  const char* key = nullptr;
  if (r.dyntype == "none" || r.dyntype == "filterexact") {
    key = "ctrlrange";
  } else if (r.dyntype == "integrator") {
    key = "actrange";
  } else {
    fail(e, "inheritrange only applies to position and intvelocity actuators (dyntype " +
                r.dyntype + ")");
  }
  const bool replaced = has_range(e, cls, key, defaults);
  const auto range = inherited_range(e, r.inheritrange, targets, defaults, ctx);
  e.set(key, format_numbers(range));
  e.set(std::string_view(key) == "actrange" ? "actlimited" : "ctrllimited", "true");
  std::string note =
      std::string("; ") + key + "=\"" + format_numbers(range) + "\" from the target range";
  if (replaced)
    note += " (it replaces the element's own " + std::string(key) + ", as in MuJoCo 3.x)";
  return note;
}

double model_timestep(const XmlNode& root) {
  double h = 0.002;
  for (const auto& c : root.children) {
    if (c.tag == "option" && c.has("timestep")) {
      const std::vector<double> v = numbers(c, "timestep");
      if (v.size() == 1 && v[0] > 0) h = v[0];
    }
  }
  return h;
}

}  // namespace

TargetIndex index_targets(const XmlNode& root) {
  TargetIndex t;
  for (const auto& c : root.children) {
    if (c.tag == "worldbody") index_joints(c, "", t.joints);
    if (c.tag != "tendon") continue;
    for (const auto& ten : c.children) {
      const std::string* name = ten.find("name");
      if (!name) continue;
      const std::string* cls = ten.find("class");
      t.tendons[*name] = {&ten, cls ? *cls : std::string("main")};
    }
  }
  return t;
}

std::vector<PendingDampratio> translate_actuators(XmlNode& root, Context& ctx,
                                                  const Defaults& defaults) {
  const double timestep = model_timestep(root);

  // 1. class records, parents first; a class whose 3.x and 2.2.2 records differ is rewritten
  std::map<std::string, ActuatorRecord> records;
  for (const auto& cls : defaults.classes()) {
    const auto parent = records.find(cls.parent);
    ActuatorRecord r3 = parent != records.end() ? parent->second : ActuatorRecord{};
    ActuatorRecord r2 = r3;  // the parent is already spelled out for 2.2.2
    bool has3 = false;
    std::vector<std::string> why;
    std::vector<std::size_t> elements;
    for (std::size_t i = 0; i < cls.node->children.size(); ++i) {
      XmlNode& e = cls.node->children[i];
      if (!is_actuator_tag(e.tag)) continue;
      elements.push_back(i);
      const bool own3 = has_3x_record_attrs(e);
      has3 = has3 || own3;
      if (own3) why.push_back(reasons(e, false));
      apply_record(r3, e, true);
      if (!own3) apply_record(r2, e, false);
    }
    records[cls.name] = r3;
    if (elements.empty() || (!has3 && r3 == r2 && r3.dyntype != "filterexact")) continue;
    if (r3.muscle) fail(*cls.node, "muscle actuator defaults with MuJoCo 3.x semantics");
    // fold the class's actuator elements into one <general> at the first one's place
    XmlNode merged = cls.node->children[elements.front()];
    for (std::size_t k = 1; k < elements.size(); ++k) {
      for (const auto& [a, v] : cls.node->children[elements[k]].attrs) merged.set(a, v);
    }
    write_general(merged, r3, timestep);
    // erased at the end: erasing now would move nested <default> elements the snapshot points to
    for (std::size_t k = 1; k < elements.size(); ++k) {
      cls.node->children[elements[k]].tag = kRemoved;
    }
    cls.node->children[elements.front()] = std::move(merged);
    std::string because;
    for (const auto& w : why) because += (because.empty() ? "" : "; ") + w;
    if (!has3) because = "parameters kept from the parent class";
    ctx.warn(*cls.node, "actuator defaults use MuJoCo 3.x semantics (" + because +
                            "); rewritten as one <general>");
  }

  // 2. actuator instances, in model order
  const TargetIndex targets = index_targets(root);
  std::vector<PendingDampratio> pending;
  std::size_t index = 0;
  for (auto& section : root.children) {
    if (section.tag != "actuator") continue;
    for (auto& e : section.children) {
      const std::size_t id = index++;
      if (!is_actuator_tag(e.tag)) continue;
      const std::string* c = e.find("class");
      const auto rec = records.find(c ? *c : std::string("main"));
      ActuatorRecord r3 = rec != records.end() ? rec->second : ActuatorRecord{};
      ActuatorRecord r2 = r3;
      const bool has3 = has_3x_record_attrs(e);
      apply_record(r3, e, true);
      if (!has3) apply_record(r2, e, false);
      const bool dampratio = r3.gainprm[0] == -r3.biasprm[1] && r3.biasprm[2] > 0;
      if (!has3 && r3 == r2 && !dampratio && r3.inheritrange <= 0 && r3.dyntype != "filterexact") {
        continue;
      }
      if (r3.muscle) fail(e, "muscle actuator with MuJoCo 3.x semantics is not translated");

      const std::string where = label(e);  // before the rewrite renames the element
      std::string note = reasons(e, !has3 && !(r3 == r2));
      if (r3.inheritrange > 0)
        note += apply_inheritrange(e, r3, c ? *c : "main", targets, defaults, ctx);
      if (dampratio) {
        pending.push_back({id, r3.biasprm[2], ctx.warnings.size()});
        note += "; dampratio " + format_numbers(std::array<double, 1>{r3.biasprm[2]}) +
                " converted to damping from the inertia at qpos0";
        r3.biasprm[2] = 0;  // placeholder until resolve_dampratios()
      }
      if (r3.dyntype == "filterexact") {
        note +=
            "; dyntype filterexact written as filter with the time constant that gives the "
            "same discrete update at timestep " +
            format_numbers(std::array<double, 1>{timestep});
      }
      const std::string tag = e.tag;
      write_general(e, r3, timestep);
      if (note.rfind("; ", 0) == 0) note = note.substr(2);
      ctx.warnings.push_back(where + ": <" + tag + "> uses MuJoCo 3.x semantics (" + note +
                             "); rewritten as <general gainprm=\"" + *e.find("gainprm") +
                             "\" biasprm=\"" + *e.find("biasprm") + "\">");
    }
  }

  translate_actuator_force_limits(root, ctx, defaults, targets);
  for (const auto& cls : defaults.classes()) {
    auto& ch = cls.node->children;
    ch.erase(
        std::remove_if(ch.begin(), ch.end(), [](const XmlNode& n) { return n.tag == kRemoved; }),
        ch.end());
  }
  return pending;
}

}  // namespace mjarm::mjcf_detail
