// MJCF translation MuJoCo 3.x -> 2.2.2: the pipeline, and the autolimits default.
//
// parse -> inline <include> -> compiler settings and absolute asset paths -> snapshot defaults
// -> expand <replicate> and <frame> -> actuators -> rule table -> autolimits -> schema check
// -> dampratio (needs a compile) -> write.

#include "mjarm/model/mjcf_translate.hpp"

#include <algorithm>

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm {

namespace mjcf_detail {

namespace {

// (range attribute, its limited flag) of the elements autolimits governs
constexpr std::pair<const char*, const char*> kJointLimits[] = {{"range", "limited"}};
constexpr std::pair<const char*, const char*> kActuatorLimits[] = {
    {"ctrlrange", "ctrllimited"}, {"forcerange", "forcelimited"}, {"actrange", "actlimited"}};

template <std::size_t N>
bool relies_on_autolimits(const XmlNode& e, const std::string& cls, std::string_view kind,
                          const std::pair<const char*, const char*> (&pairs)[N],
                          const Defaults& defaults) {
  for (const auto& [range, limited] : pairs) {
    const std::string* own_range = e.find(range);
    const std::string* own_limited = e.find(limited);
    const auto r = own_range ? std::optional(*own_range) : defaults.lookup(cls, kind, range);
    const auto l = own_limited ? std::optional(*own_limited) : defaults.lookup(cls, kind, limited);
    if ((r && !l) || l == "auto") return true;
  }
  return false;
}

bool joints_rely(const XmlNode& body, const std::string& cc, const Defaults& defaults) {
  const std::string* own = body.tag == "body" ? body.find("childclass") : nullptr;
  const std::string childclass = own ? *own : cc;
  for (const auto& c : body.children) {
    if (c.tag == "joint") {
      const std::string* cls = c.find("class");
      const std::string k = cls ? *cls : (childclass.empty() ? "main" : childclass);
      if (relies_on_autolimits(c, k, "joint", kJointLimits, defaults)) return true;
    } else if (c.tag == "body" && joints_rely(c, childclass, defaults)) {
      return true;
    }
  }
  return false;
}

}  // namespace

void ensure_autolimits(XmlNode& root, Context& ctx, const Defaults& defaults) {
  for (const auto& c : root.children) {
    if (c.tag == "compiler" && c.has("autolimits")) return;
  }
  bool needed = false;
  for (const auto& c : root.children) {
    if (c.tag == "worldbody") needed = needed || joints_rely(c, "", defaults);
    for (const auto& e : c.children) {
      const std::string* cls = e.find("class");
      const std::string k = cls ? *cls : "main";
      if (c.tag == "tendon") {
        needed = needed || relies_on_autolimits(e, k, "tendon", kJointLimits, defaults);
      } else if (c.tag == "actuator") {
        needed = needed || relies_on_autolimits(e, k, "actuator", kActuatorLimits, defaults);
      }
    }
  }
  if (!needed) return;
  auto it = std::find_if(root.children.begin(), root.children.end(),
                         [](const XmlNode& c) { return c.tag == "compiler"; });
  if (it == root.children.end()) {
    XmlNode compiler;
    compiler.tag = "compiler";
    compiler.line = root.line;
    compiler.file = root.file;
    it = root.children.insert(root.children.begin(), std::move(compiler));
  }
  it->set("autolimits", "true");
  ctx.warn(*it,
           "ranges without limited flags rely on autolimits, true by default in MuJoCo 3.x "
           "(false in 2.2.2); set autolimits=\"true\"");
}

}  // namespace mjcf_detail

std::string MjcfTranslation::to_source_lines(std::string_view message) const {
  return mjcf_detail::to_source_lines(message, source_lines);
}

MjcfTranslation translate_mjcf(std::string_view xml, const std::filesystem::path& base_dir,
                               const std::filesystem::path& source_file) {
  using namespace mjcf_detail;
  Context ctx;
  // an empty base_dir means the working directory
  ctx.base_dir =
      (base_dir.empty() ? std::filesystem::current_path() : std::filesystem::absolute(base_dir))
          .lexically_normal();
  XmlNode root = parse_document(
      xml,
      source_file.empty() ? nullptr : std::make_shared<const std::filesystem::path>(source_file));
  if (root.tag != "mujoco") fail(root, "the root element must be <mujoco>");

  inline_includes(root, ctx);
  resolve_compiler_and_paths(root, ctx);
  std::vector<PendingDampratio> pending;
  {
    Defaults defaults(root);
    expand_replicates(root, ctx, defaults);
    expand_frames(root, ctx, defaults);
    pending = translate_actuators(root, ctx, defaults);
    apply_rules(root, ctx);
    // may insert a <compiler> at the top: the last pass that consults the defaults snapshot
    ensure_autolimits(root, ctx, defaults);
  }
  check_schema(root);
  resolve_dampratios(root, pending, ctx.warnings);
  MjcfTranslation result;
  result.xml = write_document(root, &result.source_lines);
  result.warnings = std::move(ctx.warnings);
  return result;
}

}  // namespace mjarm
