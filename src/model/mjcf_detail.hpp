#pragma once
// Internal pieces of the MJCF 3.x -> 2.2.2 translator (see mjcf_translate.cpp for the pipeline).
// Not installed: only the translator's .cpp files include this header.

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mjarm::mjcf_detail {

/// One XML element with its attributes in document order and its element children.
/// Text content and comments are not kept: MJCF ignores them.
struct XmlNode {
  std::string tag;
  std::vector<std::pair<std::string, std::string>> attrs;
  std::vector<XmlNode> children;
  int line = 0;                                       ///< 1-based line in its source file
  std::shared_ptr<const std::filesystem::path> file;  ///< source file, null for the input text

  /// Value of attribute `key`, or null when absent.
  const std::string* find(std::string_view key) const;
  bool has(std::string_view key) const { return find(key) != nullptr; }
  /// Sets `key`, replacing an existing value in place or appending a new attribute.
  void set(std::string_view key, std::string value);
  /// Removes `key`; returns whether it was present.
  bool erase(std::string_view key);
};

/// "position 'shoulder' (line 12)" or "... (line 4 of /abs/arm.xml)" for included content.
std::string label(const XmlNode& n);
/// Throws mjarm::Error "MJCF translation: <label>: <what>".
[[noreturn]] void fail(const XmlNode& n, const std::string& what);

/// Numbers of attribute `key` of `n` (empty when absent); throws naming the element if not numeric.
std::vector<double> numbers(const XmlNode& n, std::string_view key);
/// Numbers of a raw attribute value; `n` and `key` only name the source in errors.
std::vector<double> parse_numbers(const XmlNode& n, std::string_view key, std::string_view text);
/// Space-separated shortest round-trip decimal form of `v`.
std::string format_numbers(std::span<const double> v);

/// Parses an XML document into XmlNode form; throws mjarm::Error with tinyxml2's message and line.
XmlNode parse_document(std::string_view text, std::shared_ptr<const std::filesystem::path> file);
/// Serializes `root` as an indented XML document.
std::string write_document(const XmlNode& root);
/// The whole text of a model file; throws mjarm::Error naming the file when it is missing, a
/// directory or unreadable.
std::string read_model_file(const std::filesystem::path& path);

/// Calls `fn(node, parent)` for every element below `root` in pre-order (parent is never null).
template <class Fn>
void for_each_element(XmlNode& root, Fn&& fn) {
  for (auto& child : root.children) {
    fn(child, root);
    for_each_element(child, fn);
  }
}

/// State shared by the passes.
struct Context {
  std::filesystem::path base_dir;
  bool degrees = true;           ///< compiler angle="degree" (the MJCF default)
  std::string eulerseq = "xyz";  ///< compiler eulerseq
  std::vector<std::string> warnings;
  /// Records one rewrite of element `n`.
  void warn(const XmlNode& n, const std::string& what);
};

/// Snapshot of the `<default>` classes (taken once the includes are inlined).
class Defaults {
 public:
  explicit Defaults(XmlNode& root);
  /// The value `attr` takes for an element of default kind `kind` (joint, geom, tendon, ...) in
  /// class `cls`, searching `cls` then its ancestors; nullopt when no class sets it.
  std::optional<std::string> lookup(const std::string& cls, std::string_view kind,
                                    std::string_view attr) const;
  /// Classes in definition order (every parent before its children).
  struct Class {
    std::string name;
    std::string parent;  ///< empty for "main"
    XmlNode* node;       ///< the <default> element in the live tree; valid until
                         ///< translate_actuators() returns (it erases actuator defaults last)
  };
  const std::vector<Class>& classes() const { return classes_; }
  bool has(const std::string& cls) const { return index_.count(cls) > 0; }

 private:
  std::vector<Class> classes_;
  std::map<std::string, std::size_t> index_;
  // class -> kind -> attribute -> value, copied so later passes cannot disturb the lookups
  std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> values_;
};

/// Whether `tag` is one of the actuator elements MuJoCo 2.2.2 knows (general, motor, ...).
bool is_actuator_tag(std::string_view tag);
/// The default kind an element tag reads from ("spatial" and "fixed" read "tendon"; every
/// actuator shortcut reads the class's one "actuator" default).
std::string_view default_kind(std::string_view tag);

/// Unit quaternion (w, x, y, z) and small helpers for composing frames.
using Quat = std::array<double, 4>;
using Vec3 = std::array<double, 3>;
Quat quat_mul(const Quat& a, const Quat& b);
Vec3 quat_rotate(const Quat& q, const Vec3& v);
/// Orientation of an element from its quat / axisangle / xyaxes / zaxis / euler attributes
/// (nullopt when it has none); throws when several are present.
std::optional<Quat> read_orientation(const XmlNode& n, const Context& ctx);
/// Removes every orientation attribute of `n`.
void erase_orientation(XmlNode& n);

// ---- passes, in pipeline order ----

/// Inlines every <include file> below `root` (recursively, cycle-checked).
void inline_includes(XmlNode& root, Context& ctx);
/// Reads compiler angle / eulerseq and makes every asset file path absolute.
void resolve_compiler_and_paths(XmlNode& root, Context& ctx);
/// Expands <replicate> elements whose content can be reproduced exactly.
void expand_replicates(XmlNode& root, Context& ctx, const Defaults& defaults);
/// Replaces every <frame> by its children with the frame pose composed into them.
void expand_frames(XmlNode& root, Context& ctx, const Defaults& defaults);

/// An actuator whose 3.x dampratio still has to be turned into a damping gain.
struct PendingDampratio {
  std::size_t actuator_index;  ///< position in the compiled model's actuator list
  double dampratio;
  std::size_t warning_index;  ///< the rewrite's warning, whose biasprm is updated too
};
/// Rewrites actuators (and actuator defaults) into 2.2.2 form, moves joint / tendon
/// actuatorfrcrange into actuator forceranges, and returns the dampratios left to resolve.
std::vector<PendingDampratio> translate_actuators(XmlNode& root, Context& ctx,
                                                  const Defaults& defaults);
/// Applies the table of (element, attribute) rules and the element rules (dropped sensors, ...).
void apply_rules(XmlNode& root, Context& ctx);
/// Adds compiler autolimits="true" (the 3.x default) when some range relies on it.
void ensure_autolimits(XmlNode& root, Context& ctx, const Defaults& defaults);
/// Throws when an element or attribute is still unknown to the installed MuJoCo's schema.
void check_schema(const XmlNode& root);
/// Compiles `root` with MuJoCo 2.2.2 and writes the damping implied by each pending dampratio.
void resolve_dampratios(XmlNode& root, const std::vector<PendingDampratio>& pending,
                        std::vector<std::string>& warnings);

}  // namespace mjarm::mjcf_detail
