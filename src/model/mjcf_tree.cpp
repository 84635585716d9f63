// XML element tree of the MJCF staging: parsing (tinyxml2), writing, attribute helpers.

#include <tinyxml2.h>

#include <cctype>
#include <cstdlib>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

const std::string* XmlNode::find(std::string_view key) const {
  for (const auto& [k, v] : attrs) {
    if (k == key) return &v;
  }
  return nullptr;
}

void XmlNode::set(std::string_view key, std::string value) {
  for (auto& [k, v] : attrs) {
    if (k == key) {
      v = std::move(value);
      return;
    }
  }
  attrs.emplace_back(std::string(key), std::move(value));
}

bool XmlNode::erase(std::string_view key) {
  for (auto it = attrs.begin(); it != attrs.end(); ++it) {
    if (it->first == key) {
      attrs.erase(it);
      return true;
    }
  }
  return false;
}

std::string label(const XmlNode& n) {
  std::string s = n.tag;
  if (const std::string* name = n.find("name")) s += " '" + *name + "'";
  s += " (line " + std::to_string(n.line);
  if (n.file) s += " of '" + n.file->string() + "'";
  return s + ")";
}

void fail(const XmlNode& n, const std::string& what) {
  throw Error("MJCF: " + label(n) + ": " + what);
}

namespace {

XmlNode convert(const tinyxml2::XMLElement& e,
                const std::shared_ptr<const std::filesystem::path>& file) {
  XmlNode n;
  n.tag = e.Name();
  n.line = e.GetLineNum();
  n.file = file;
  for (const tinyxml2::XMLAttribute* a = e.FirstAttribute(); a; a = a->Next()) {
    n.attrs.emplace_back(a->Name(), a->Value());
  }
  for (const tinyxml2::XMLElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
    n.children.push_back(convert(*c, file));
  }
  return n;
}

void escape(std::string& out, std::string_view s) {
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\n':
        out += "&#10;";
        break;
      default:
        out += c;
    }
  }
}

void note_line(std::vector<MjcfSourceLine>* lines, const XmlNode& n) {
  if (lines) lines->push_back({n.file ? *n.file : std::filesystem::path(), n.line});
}

void write(std::string& out, const XmlNode& n, int depth, std::vector<MjcfSourceLine>* lines) {
  note_line(lines, n);
  out.append(static_cast<std::size_t>(2 * depth), ' ');
  out += '<';
  out += n.tag;
  for (const auto& [k, v] : n.attrs) {
    out += ' ';
    out += k;
    out += "=\"";
    escape(out, v);
    out += '"';
  }
  if (n.children.empty()) {
    out += "/>\n";
    return;
  }
  out += ">\n";
  for (const auto& c : n.children) write(out, c, depth + 1, lines);
  note_line(lines, n);  // the closing tag
  out.append(static_cast<std::size_t>(2 * depth), ' ');
  out += "</" + n.tag + ">\n";
}

}  // namespace

std::string xml_parse_error(const tinyxml2::XMLDocument& doc, const std::string& source) {
  std::ostringstream msg;
  if (doc.ErrorID() == tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED) {
    // a well-formed but deep tree: say which limit it hit, not "malformed"
    msg << source << " nests elements more than " << TINYXML2_MAX_ELEMENT_DEPTH << " deep (line "
        << doc.ErrorLineNum()
        << "), the limit of the tinyxml2 XML parser (TINYXML2_MAX_ELEMENT_DEPTH); a chain of "
           "bodies that long cannot be read";
  } else {
    msg << "malformed XML in " << source << " (line " << doc.ErrorLineNum()
        << "): " << doc.ErrorName() << ": " << doc.ErrorStr();
  }
  return msg.str();
}

const tinyxml2::XMLElement& single_root(const tinyxml2::XMLDocument& doc,
                                        const std::string& source) {
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr) throw Error(source + " has no root element");
  if (const tinyxml2::XMLElement* second = root->NextSiblingElement()) {
    throw Error(source + " line " + std::to_string(second->GetLineNum()) +
                ": a second root element <" + second->Name() + "> (the first, <" + root->Name() +
                ">, is at line " + std::to_string(root->GetLineNum()) +
                "); an XML file holds one: remove the second or put it in a file of its own");
  }
  return *root;
}

XmlNode parse_document(std::string_view text, std::shared_ptr<const std::filesystem::path> file) {
  tinyxml2::XMLDocument doc;
  const std::string source = file ? "'" + file->string() + "'" : std::string("<input>");
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    throw Error("MJCF: " + xml_parse_error(doc, source));
  }
  try {
    return convert(single_root(doc, source), file);
  } catch (const Error& e) {
    throw Error(std::string("MJCF: ") + e.what());
  }
}

std::string write_document(const XmlNode& root, std::vector<MjcfSourceLine>* lines) {
  std::string out;
  if (lines) lines->clear();
  write(out, root, 0, lines);
  return out;
}

std::string to_source_lines(std::string_view message, const std::vector<MjcfSourceLine>& lines) {
  // MuJoCo writes "Element 'geom', line 5" (XML errors), "Element name 'g', id 0, line 5"
  // (compiler errors), and older versions "Object name = m, id = 0, line = 5, column = -1"
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const std::size_t at = message.find("line ", i);
    if (at == std::string_view::npos) break;
    std::size_t p = at + 5;
    if (message.compare(p, 2, "= ") == 0) p += 2;
    std::size_t end = p;
    while (end < message.size() && message[end] >= '0' && message[end] <= '9') ++end;
    const bool word = at == 0 || !std::isalnum(static_cast<unsigned char>(message[at - 1]));
    if (end == p || !word) {
      out.append(message.substr(i, p - i));
      i = p;
      continue;
    }
    const long n = std::strtol(std::string(message.substr(p, end - p)).c_str(), nullptr, 10);
    out.append(message.substr(i, at - i));
    if (n >= 1 && static_cast<std::size_t>(n) <= lines.size()) {
      const MjcfSourceLine& source = lines[static_cast<std::size_t>(n - 1)];
      out += "line " + std::to_string(source.line);
      if (!source.file.empty()) out += " of '" + source.file.string() + "'";
      // the column counts in the staged text (includes inlined): meaningless to the user
      const std::string_view column = ", column = ";
      if (message.compare(end, column.size(), column) == 0) {
        end += column.size();
        if (end < message.size() && message[end] == '-') ++end;
        while (end < message.size() && message[end] >= '0' && message[end] <= '9') ++end;
      }
    } else {
      out.append(message.substr(at, end - at));
    }
    i = end;
  }
  out.append(message.substr(i));
  return out;
}

}  // namespace mjarm::mjcf_detail
