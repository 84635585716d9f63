#pragma once
// Internal pieces of the MJCF staging (mjcf_staging.cpp): an element tree with source lines, its
// reader and writer.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mjcf_staging.hpp"

namespace tinyxml2 {
class XMLDocument;
class XMLElement;
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

/// "malformed XML in <source> (line N): <tinyxml2's error>", or for a tree deeper than tinyxml2
/// reads, what its depth limit (TINYXML2_MAX_ELEMENT_DEPTH) is.
std::string xml_parse_error(const tinyxml2::XMLDocument& doc, const std::string& source);
/// The root element of a parsed document.
/// @throws Error naming @p source when there is none, or a second one (tinyxml2 reads it; MuJoCo
///         and mjarm would drop it without a word).
const tinyxml2::XMLElement& single_root(const tinyxml2::XMLDocument& doc,
                                        const std::string& source);
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

// ---- the staging passes, in order ----

/// Inlines every <include file> below `root` (recursively, cycle-checked); relative paths
/// resolve against `base`, then against the including file's folder.
void inline_includes(XmlNode& root, const std::filesystem::path& base);
/// Makes every asset file path absolute (compiler meshdir / texturedir / assetdir, strippath)
/// and checks each existing file; removes those compiler settings. With @p missing_meshes, a
/// mesh whose file is not found is no error: it is dropped, each geom showing it becomes a box
/// (replace_missing_meshes) and one message per missing file is appended.
void resolve_asset_paths(XmlNode& root, const std::filesystem::path& base,
                         std::vector<std::string>* missing_meshes = nullptr);

}  // namespace mjarm::mjcf_detail
