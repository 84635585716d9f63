#pragma once
// Internal pieces of the MJCF staging (mjcf_staging.cpp) and of the scene's MJCF parts: an
// element tree with source lines, its reader and writer, <default> lookups, orientations.

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

#include "mjarm/model/mjcf_staging.hpp"

namespace tinyxml2 {
class XMLDocument;
}

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

/// "position 'shoulder' (line 12)" or "... (line 4 of '/abs/arm.xml')" when the element's file is
/// known.
std::string label(const XmlNode& n);
/// Throws mjarm::Error "MJCF: <label>: <what>".
[[noreturn]] void fail(const XmlNode& n, const std::string& what);

/// Numbers of attribute `key` of `n` (empty when absent); throws naming the element if not numeric.
std::vector<double> numbers(const XmlNode& n, std::string_view key);
/// Numbers of a raw attribute value; `n` and `key` only name the source in errors.
std::vector<double> parse_numbers(const XmlNode& n, std::string_view key, std::string_view text);
/// Space-separated shortest round-trip decimal form of `v`.
std::string format_numbers(std::span<const double> v);

/// "malformed XML in <source> (line N): <tinyxml2's error>", or for a tree deeper than tinyxml2
/// reads, what its depth limit (TINYXML2_MAX_ELEMENT_DEPTH) is.
std::string xml_parse_error(const tinyxml2::XMLDocument& doc, const std::string& source);
/// Parses an XML document into XmlNode form; throws mjarm::Error with tinyxml2's message and line.
XmlNode parse_document(std::string_view text, std::shared_ptr<const std::filesystem::path> file);
/// Serializes `root` as an indented XML document, one element per line; when `lines` is given,
/// fills it with the source of each output line.
std::string write_document(const XmlNode& root, std::vector<MjcfSourceLine>* lines = nullptr);
/// `message` with each "line N" of a written document mapped through `lines` to its source.
std::string to_source_lines(std::string_view message, const std::vector<MjcfSourceLine>& lines);

/// Calls `fn(node, parent)` for every element below `root` in pre-order (parent is never null).
template <class Fn>
void for_each_element(XmlNode& root, Fn&& fn) {
  for (auto& child : root.children) {
    fn(child, root);
    for_each_element(child, fn);
  }
}

/// The compiler settings that give angles their meaning.
struct Context {
  bool degrees = true;           ///< compiler angle="degree" (the MJCF default)
  std::string eulerseq = "xyz";  ///< compiler eulerseq
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
    XmlNode* node;       ///< the <default> element in the live tree
  };
  const std::vector<Class>& classes() const { return classes_; }
  bool has(const std::string& cls) const { return index_.count(cls) > 0; }

 private:
  std::vector<Class> classes_;
  std::map<std::string, std::size_t> index_;
  // class -> kind -> attribute -> value, copied so later passes cannot disturb the lookups
  std::map<std::string, std::map<std::string, std::map<std::string, std::string>>> values_;
};

/// Whether `tag` is one of the actuator elements (general, motor, position, ...).
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

// ---- the staging passes, in order ----

/// Inlines every <include file> below `root` (recursively, cycle-checked); relative paths
/// resolve against `base`, then against the including file's folder.
void inline_includes(XmlNode& root, const std::filesystem::path& base);
/// Makes every asset file path absolute (compiler meshdir / texturedir / assetdir, strippath)
/// and checks each existing file; removes those compiler settings.
void resolve_asset_paths(XmlNode& root, const std::filesystem::path& base);

}  // namespace mjarm::mjcf_detail
