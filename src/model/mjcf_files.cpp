// <include> inlining and asset path resolution of the MJCF translator.

#include <fstream>
#include <set>
#include <sstream>

#include "mjarm/error.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace fs = std::filesystem;

namespace {

// MuJoCo resolves include and asset paths against the main file's directory; newer 3.x versions
// also try the directory of the included file that names them
std::optional<fs::path> locate(const fs::path& file, const fs::path& base, const XmlNode& from) {
  if (file.is_absolute()) return fs::exists(file) ? std::optional(file) : std::nullopt;
  const fs::path main = (base / file).lexically_normal();
  if (fs::exists(main)) return main;
  if (from.file) {
    const fs::path local = (from.file->parent_path() / file).lexically_normal();
    if (fs::exists(local)) return local;
  }
  return std::nullopt;
}

void inline_in(XmlNode& parent, Context& ctx, std::vector<fs::path>& stack,
               std::set<fs::path>& seen) {
  std::vector<XmlNode> out;
  for (auto& c : parent.children) {
    if (c.tag != "include") {
      inline_in(c, ctx, stack, seen);
      out.push_back(std::move(c));
      continue;
    }
    const std::string* name = c.find("file");
    if (!name) fail(c, "<include> needs a file attribute");
    const auto path = locate(*name, ctx.base_dir, c);
    if (!path) {
      fail(c, "included file '" + *name + "' not found (looked in " + ctx.base_dir.string() +
                  (c.file ? " and " + c.file->parent_path().string() : std::string()) + ")");
    }
    const fs::path canonical = fs::weakly_canonical(*path);
    for (const auto& open : stack) {
      if (open == canonical) fail(c, "include cycle through '" + canonical.string() + "'");
    }
    if (!seen.insert(canonical).second) {
      fail(c, "'" + canonical.string() + "' is included twice (MuJoCo allows one inclusion)");
    }
    std::ifstream in(canonical, std::ios::binary);
    if (!in) fail(c, "cannot read included file '" + canonical.string() + "'");
    std::ostringstream text;
    text << in.rdbuf();
    XmlNode included = parse_document(text.str(), std::make_shared<const fs::path>(canonical));
    if (included.tag != "mujoco") fail(included, "an included file's root must be <mujoco>");
    stack.push_back(canonical);
    inline_in(included, ctx, stack, seen);
    stack.pop_back();
    for (auto& ic : included.children) out.push_back(std::move(ic));
  }
  parent.children = std::move(out);
}

bool is_file_attr(std::string_view tag, std::string_view key) {
  if (tag == "texture") {
    return key == "file" || key == "fileright" || key == "fileleft" || key == "fileup" ||
           key == "filedown" || key == "filefront" || key == "fileback";
  }
  return (tag == "mesh" || tag == "hfield" || tag == "skin") && key == "file";
}

}  // namespace

std::string read_model_file(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("model file '" + path.string() + "' does not exist");
  if (fs::is_directory(path, ec))
    throw Error("model path '" + path.string() + "' is a directory, expected an MJCF or URDF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("model file '" + path.string() + "' cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void inline_includes(XmlNode& root, Context& ctx) {
  std::vector<fs::path> stack;
  std::set<fs::path> seen;
  inline_in(root, ctx, stack, seen);
}

void resolve_compiler_and_paths(XmlNode& root, Context& ctx) {
  // compiler settings are global; later elements override earlier ones
  std::string meshdir, texturedir, assetdir;
  bool strip = false;
  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    if (const std::string* v = c.find("angle")) ctx.degrees = *v != "radian";
    if (const std::string* v = c.find("eulerseq")) ctx.eulerseq = *v;
    if (const std::string* v = c.find("meshdir")) meshdir = *v;
    if (const std::string* v = c.find("texturedir")) texturedir = *v;
    if (const std::string* v = c.find("assetdir")) assetdir = *v;
    if (const std::string* v = c.find("strippath")) strip = *v == "true";
  }
  // 3.x assetdir stands in for whichever of meshdir / texturedir is not given
  if (meshdir.empty()) meshdir = assetdir;
  if (texturedir.empty()) texturedir = assetdir;

  for_each_element(root, [&](XmlNode& e, XmlNode&) {
    for (auto& [key, value] : e.attrs) {
      if (!is_file_attr(e.tag, key) || value.empty()) continue;
      fs::path file = strip ? fs::path(value).filename() : fs::path(value);
      if (file.is_absolute()) continue;
      const fs::path dir = e.tag == "texture" ? fs::path(texturedir) : fs::path(meshdir);
      const fs::path rel = dir / file;
      const auto found = locate(rel, ctx.base_dir, e);
      // a missing file is reported by MuJoCo when it loads the model
      value = found ? found->string()
                    : (rel.is_absolute() ? rel : ctx.base_dir / rel).lexically_normal().string();
    }
  });

  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    for (const char* key : {"meshdir", "texturedir"}) {
      if (const std::string* v = c.find(key); v && fs::path(*v).is_relative()) {
        c.set(key, (ctx.base_dir / *v).lexically_normal().string());
      }
    }
    // paths are already stripped; stripping again would drop the absolute directories
    c.erase("strippath");
    if (const std::string* v = c.find("assetdir")) {
      ctx.warn(c, "assetdir=\"" + *v + "\" is MuJoCo 3.x; asset paths were resolved against it");
      c.erase("assetdir");
    }
  }
}

}  // namespace mjarm::mjcf_detail
