// <include> inlining and asset path resolution of the MJCF staging (mjcf_staging.hpp).

#include <functional>
#include <map>
#include <optional>
#include <set>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjarm/number_text.hpp"
#include "mjcf_detail.hpp"

namespace mjarm::mjcf_detail {

namespace fs = std::filesystem;

namespace {

// whether a directory entry exists at `p` (a dangling link or a link loop counts: reading it
// reports what is wrong with it, instead of "not found")
bool entry_exists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

// MuJoCo resolves include and asset paths against the main file's directory, then against the
// directory of the included file that names them
std::optional<fs::path> locate(const fs::path& file, const fs::path& base, const XmlNode& from) {
  if (file.is_absolute()) return entry_exists(file) ? std::optional(file) : std::nullopt;
  const fs::path main = (base / file).lexically_normal();
  if (entry_exists(main)) return main;
  if (from.file) {
    const fs::path local = (from.file->parent_path() / file).lexically_normal();
    if (entry_exists(local)) return local;
  }
  return std::nullopt;
}

// reads an included file through the one checked reader; its errors name the <include>
std::string read_include(const XmlNode& include, const fs::path& path) {
  try {
    return read_user_file(path, "included file");
  } catch (const Error& e) {
    fail(include, e.what());
  }
}

void inline_in(XmlNode& parent, const fs::path& base, std::vector<fs::path>& stack,
               std::set<fs::path>& seen) {
  std::vector<XmlNode> out;
  for (auto& c : parent.children) {
    if (c.tag != "include") {
      inline_in(c, base, stack, seen);
      out.push_back(std::move(c));
      continue;
    }
    const std::string* name = c.find("file");
    if (!name) fail(c, "<include> needs a file attribute");
    const auto path = locate(*name, base, c);
    if (!path) {
      fail(c, "included file '" + *name + "' not found (looked in " + base.string() +
                  (c.file ? " and " + c.file->parent_path().string() : std::string()) + ")");
    }
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(*path, ec);
    if (ec) canonical = *path;  // a link loop: read_include() reports it
    for (const auto& open : stack) {
      if (open == canonical) fail(c, "include cycle through '" + canonical.string() + "'");
    }
    if (!seen.insert(canonical).second) {
      fail(c, "'" + canonical.string() + "' is included twice (MuJoCo allows one inclusion)");
    }
    const std::string text = read_include(c, canonical);
    XmlNode included = parse_document(text, std::make_shared<const fs::path>(canonical));
    if (included.tag != "mujoco") fail(included, "an included file's root must be <mujoco>");
    stack.push_back(canonical);
    inline_in(included, base, stack, seen);
    stack.pop_back();
    for (auto& ic : included.children) out.push_back(std::move(ic));
  }
  parent.children = std::move(out);
}

// MuJoCo opens the assets itself: they get the same checks before it does
void check_asset(const XmlNode& e, const std::string& key, const fs::path& path) {
  try {
    check_user_file(path, e.tag + " " + key, kMaxDataFileBytes);
  } catch (const Error& err) {
    fail(e, err.what());
  }
}

bool is_file_attr(std::string_view tag, std::string_view key) {
  if (tag == "texture") {
    return key == "file" || key == "fileright" || key == "fileleft" || key == "fileup" ||
           key == "filedown" || key == "filefront" || key == "fileback";
  }
  return (tag == "mesh" || tag == "hfield" || tag == "skin" || tag == "model") && key == "file";
}

// Drops the meshes of @p missing and turns each geom showing one (in a body or a default class)
// into a box of its own size, else kMissingMeshBoxHalfSize; one message per missing file.
void replace_missing_meshes(XmlNode& root, const std::map<std::string, std::string>& missing,
                            std::vector<std::string>& messages) {
  std::map<std::string, int> geoms;  // mesh name -> geoms turned into boxes
  for_each_element(root, [&](XmlNode& e, XmlNode&) {
    if (e.tag != "geom") return;
    const std::string* mesh = e.find("mesh");
    if (mesh == nullptr || missing.count(*mesh) == 0) return;
    ++geoms[*mesh];
    e.erase("mesh");
    e.set("type", "box");
    if (!e.has("size")) {
      const std::string half = number_text(kMissingMeshBoxHalfSize);
      e.set("size", half + " " + half + " " + half);
    }
  });
  std::function<void(XmlNode&)> drop = [&](XmlNode& parent) {
    std::erase_if(parent.children, [&](const XmlNode& c) {
      if (c.tag != "mesh") return false;
      const std::string* name = c.find("name");
      const std::string* file = c.find("file");
      const std::string key = name != nullptr   ? *name
                              : file != nullptr ? fs::path(*file).stem().string()
                                                : std::string();
      return !key.empty() && missing.count(key) != 0;
    });
    for (XmlNode& c : parent.children) drop(c);
  };
  drop(root);
  std::set<std::string> said;
  for (const auto& [name, what] : missing) {
    if (!said.insert(what).second) continue;  // one message per file
    const int n = geoms.count(name) != 0 ? geoms.at(name) : 0;
    messages.push_back("mesh '" + name + "': " + what + ": " +
                       (n == 0 ? std::string("no geom shows it")
                               : "its " + std::to_string(n) + (n == 1 ? " geom is" : " geoms are") +
                                     " drawn as a box (its own size, else half-size " +
                                     number_text(kMissingMeshBoxHalfSize) + " m)"));
  }
}

}  // namespace

void inline_includes(XmlNode& root, const fs::path& base) {
  std::vector<fs::path> stack;
  std::set<fs::path> seen;
  inline_in(root, base, stack, seen);
}

void resolve_asset_paths(XmlNode& root, const fs::path& base,
                         std::vector<std::string>* missing_meshes) {
  std::map<std::string, std::string> missing;  // mesh name -> what is missing
  // compiler settings are global; later elements override earlier ones
  std::string meshdir, texturedir, assetdir;
  bool strip = false;
  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    if (const std::string* v = c.find("meshdir")) meshdir = *v;
    if (const std::string* v = c.find("texturedir")) texturedir = *v;
    if (const std::string* v = c.find("assetdir")) assetdir = *v;
    if (const std::string* v = c.find("strippath")) strip = *v == "true";
  }
  // assetdir stands in for whichever of meshdir / texturedir is not given
  if (meshdir.empty()) meshdir = assetdir;
  if (texturedir.empty()) texturedir = assetdir;

  for_each_element(root, [&](XmlNode& e, XmlNode&) {
    for (auto& [key, value] : e.attrs) {
      if (!is_file_attr(e.tag, key) || value.empty()) continue;
      const fs::path file = strip ? fs::path(value).filename() : fs::path(value);
      const fs::path dir = e.tag == "texture" ? fs::path(texturedir) : fs::path(meshdir);
      const fs::path rel = file.is_absolute() ? file : dir / file;
      const auto found = locate(rel, base, e);
      // MuJoCo's own message for a missing file names neither the element nor the line
      if (!found) {
        const fs::path main = (rel.is_absolute() ? rel : base / rel).lexically_normal();
        const fs::path local =
            e.file ? (e.file->parent_path() / rel).lexically_normal() : fs::path();
        const std::string looked =
            "looked for " + main.string() +
            (e.file && !rel.is_absolute() && local != main ? " and " + local.string()
                                                           : std::string());
        if (missing_meshes != nullptr && e.tag == "mesh") {
          // MuJoCo names a mesh without a name after its file
          const std::string* name = e.find("name");
          missing[name != nullptr ? *name : fs::path(value).stem().string()] =
              "mesh file '" + value + "' not found (" + looked + ")";
          continue;
        }
        fail(e, key + " '" + value + "' not found (" + looked + ")");
      }
      check_asset(e, key, *found);
      value = found->string();
    }
  });

  if (!missing.empty()) replace_missing_meshes(root, missing, *missing_meshes);
  // every path is absolute now: the folders and the stripping have done their part
  for (auto& c : root.children) {
    if (c.tag != "compiler") continue;
    for (const char* key : {"meshdir", "texturedir", "assetdir", "strippath"}) c.erase(key);
  }
}

}  // namespace mjarm::mjcf_detail
