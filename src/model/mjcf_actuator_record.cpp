// How each MJCF actuator element changes the per-class actuator record, under the MuJoCo 3.x
// rules and under the MuJoCo 2.2.2 rules (the latter measured by loading models in 2.2.2).

#include "mjcf_actuator_record.hpp"

#include <numbers>
#include <optional>

namespace mjarm::mjcf_detail {

namespace {

std::optional<double> scalar(const XmlNode& e, const char* key) {
  const std::vector<double> v = numbers(e, key);
  if (v.empty()) return std::nullopt;
  if (v.size() != 1) fail(e, std::string(key) + " needs one number");
  return v[0];
}

// MJCF reads a parameter list into the first entries and keeps the rest
void read_prefix(const XmlNode& e, const char* key, std::array<double, kNumPrm>& dst,
                 std::size_t max = kNumPrm) {
  const std::vector<double> v = numbers(e, key);
  if (v.size() > max)
    fail(e, std::string(key) + " has more than " + std::to_string(max) + " numbers");
  for (std::size_t i = 0; i < v.size(); ++i) dst[i] = v[i];
}

void non_negative(const XmlNode& e, const char* key, const std::optional<double>& v) {
  if (v && *v < 0) fail(e, std::string(key) + " cannot be negative");
}

void servo(ActuatorRecord& r, const XmlNode& e, bool v3) {
  const double kp = scalar(e, "kp").value_or(r.gainprm[0]);
  if (v3) {
    // 3.x: kv / dampratio go to biasprm[2]; anything not given stays as the class left it
    const auto kv = scalar(e, "kv");
    const auto dampratio = scalar(e, "dampratio");
    const auto timeconst = scalar(e, "timeconst");
    if (kv && dampratio) fail(e, "kv and dampratio cannot both be defined");
    non_negative(e, "kv", kv);
    non_negative(e, "dampratio", dampratio);
    non_negative(e, "timeconst", timeconst);
    r.gainprm[0] = kp;
    r.biasprm[1] = -kp;
    if (kv) r.biasprm[2] = -*kv;
    if (dampratio) r.biasprm[2] = *dampratio;
    if (timeconst) {
      r.dynprm[0] = *timeconst;
      r.dyntype = *timeconst == 0 ? "none" : "filterexact";
    }
    if (const auto ir = scalar(e, "inheritrange")) r.inheritrange = *ir;
  } else {
    // 2.2.2: bias reset to (0, -kp, 0, ...), no activation dynamics
    r.biasprm.fill(0);
    r.gainprm[0] = kp;
    r.biasprm[1] = -kp;
    r.dyntype = "none";
  }
  r.gaintype = "fixed";
  r.biastype = "affine";
  if (e.tag == "intvelocity") {
    r.dyntype = "integrator";
    r.force_actlimited = true;
  }
}

}  // namespace

bool has_3x_record_attrs(const XmlNode& e) {
  if (e.tag != "position" && e.tag != "intvelocity") return false;
  return e.has("kv") || e.has("dampratio") || e.has("timeconst") || e.has("inheritrange");
}

void apply_record(ActuatorRecord& r, const XmlNode& e, bool v3) {
  const std::string& tag = e.tag;
  if (tag == "general") {
    if (const std::string* v = e.find("dyntype")) r.dyntype = *v;
    if (const std::string* v = e.find("gaintype")) r.gaintype = *v;
    if (const std::string* v = e.find("biastype")) r.biastype = *v;
    read_prefix(e, "dynprm", r.dynprm);
    read_prefix(e, "gainprm", r.gainprm);
    read_prefix(e, "biasprm", r.biasprm);
  } else if (tag == "motor") {
    r.gainprm[0] = 1;
    r.dyntype = "none";
    r.gaintype = "fixed";
    r.biastype = "none";
  } else if (tag == "position" || tag == "intvelocity") {
    servo(r, e, v3);
  } else if (tag == "velocity") {
    const double kv = scalar(e, "kv").value_or(r.gainprm[0]);
    r.biasprm.fill(0);
    r.gainprm[0] = kv;
    r.biasprm[2] = -kv;
    r.dyntype = "none";
    r.gaintype = "fixed";
    r.biastype = "affine";
  } else if (tag == "damper") {
    const auto kv = scalar(e, "kv");
    non_negative(e, "kv", kv);
    r.gainprm.fill(0);
    r.gainprm[2] = -kv.value_or(0);
    r.force_ctrllimited = true;
    r.dyntype = "none";
    r.gaintype = "affine";
    r.biastype = "none";
  } else if (tag == "cylinder") {
    if (const auto tc = scalar(e, "timeconst")) r.dynprm[0] = *tc;
    read_prefix(e, "bias", r.biasprm, 3);
    if (const auto area = scalar(e, "area")) r.gainprm[0] = *area;
    if (const auto d = scalar(e, "diameter")) r.gainprm[0] = std::numbers::pi / 4 * *d * *d;
    r.dyntype = "filter";
    r.gaintype = "fixed";
    r.biastype = "affine";
  } else if (tag == "muscle") {
    r.muscle = true;
    r.dyntype = "muscle";
    r.gaintype = "muscle";
    r.biastype = "muscle";
  } else if (tag == "adhesion") {
    const auto gain = scalar(e, "gain");
    non_negative(e, "gain", gain);
    r.gainprm[0] = gain.value_or(r.gainprm[0]);
    r.force_ctrllimited = true;
    r.gaintype = "fixed";
    r.biastype = "none";
  }
}

}  // namespace mjarm::mjcf_detail
