// Final check of a translated document against the installed MuJoCo's own MJCF schema (as
// printed by mj_printSchema), so anything without a translation rule is reported with its
// source line instead of surfacing later as a load error on the translated text.

#include <mujoco/mujoco.h>

#include <set>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace {

struct SchemaNode {
  std::string name;
  bool recursive = false;
  std::set<std::string> attrs;
  std::vector<std::unique_ptr<SchemaNode>> children;
};

// mj_printSchema text: one element per line, indented 3 spaces per level, "name (mult)" in the
// first 30 columns, attributes after them, continued on lines indented by 30 spaces
std::unique_ptr<SchemaNode> parse_schema(const std::string& text) {
  auto root = std::make_unique<SchemaNode>();
  std::vector<SchemaNode*> stack{root.get()};
  SchemaNode* last = nullptr;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos) continue;
    std::istringstream words(line.substr(indent));
    std::string word;
    if (indent >= 30) {
      while (last && words >> word) last->attrs.insert(word);
      continue;
    }
    const std::size_t depth = indent / 3;
    std::string name, mult;
    words >> name >> mult;
    if (name.rfind("(world)", 0) == 0) name = name.substr(7);
    auto node = std::make_unique<SchemaNode>();
    node->name = name;
    node->recursive = mult == "(R)";
    while (words >> word) node->attrs.insert(word);
    while (stack.size() > depth + 1) stack.pop_back();
    last = node.get();
    stack.back()->children.push_back(std::move(node));
    stack.push_back(last);
  }
  return root;
}

const SchemaNode& installed_schema() {
  static const std::unique_ptr<SchemaNode> schema = [] {
    std::string buf(1 << 17, '\0');
    mj_printSchema(nullptr, buf.data(), static_cast<int>(buf.size()), 0, 0);
    buf.resize(buf.find('\0'));
    return parse_schema(buf);
  }();
  return *schema;
}

const SchemaNode* child_schema(const SchemaNode& parent, const std::string& tag) {
  const std::string name = tag == "worldbody" ? "body" : tag;
  for (const auto& c : parent.children) {
    if (c->name == name) return c.get();
  }
  if (parent.recursive && parent.name == name) return &parent;
  return nullptr;
}

void check(const XmlNode& e, const SchemaNode& s) {
  for (const auto& [key, value] : e.attrs) {
    if (!s.attrs.count(key)) {
      fail(e, "attribute " + key + "=\"" + value + "\" is not known to MuJoCo " +
                  mj_versionString() + " and has no translation rule");
    }
  }
  for (const auto& c : e.children) {
    const SchemaNode* cs = child_schema(s, c.tag);
    if (!cs) {
      fail(c, "element <" + c.tag + "> inside <" + e.tag + "> is not known to MuJoCo " +
                  mj_versionString() + " and has no translation rule");
    }
    check(c, *cs);
  }
}

}  // namespace

void check_schema(const XmlNode& root) {
  const SchemaNode* top = child_schema(installed_schema(), root.tag);
  if (!top) fail(root, "the root element must be <mujoco>");
  check(root, *top);
}

}  // namespace mjarm::mjcf_detail
