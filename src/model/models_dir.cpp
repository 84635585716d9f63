// Where the bundled models are: $MJARM_MODELS, else beside the installed binary that holds this
// code, else the source tree, else the install's share dir. The folders come from CMake
// (cmake/install_dirs.cmake) as MJARM_MODELS_RELATIVE_DIRS (':'-separated, relative to the
// binary's folder: one per installed binary), MJARM_MODELS_SOURCE_DIR and MJARM_MODELS_INSTALL_DIR
// (empty in a wheel, which knows neither).

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>
#include <string_view>

#include "mjarm/model/robot.hpp"

namespace mjarm {
namespace {

// The folder of the executable or shared object this code was linked into (mjarm is a static
// library: the CLI, the Python extension or a consumer's program), empty when it cannot be told.
std::filesystem::path folder_of_this_binary() {
  Dl_info info{};
  link_map* map = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&folder_of_this_binary), &info,
              reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP) == 0 ||
      map == nullptr || map->l_name == nullptr) {
    return {};
  }
  std::error_code ec;
  // the main program's entry has no name: its file is /proc/self/exe
  const std::filesystem::path file = *map->l_name == '\0'
                                         ? std::filesystem::read_symlink("/proc/self/exe", ec)
                                         : std::filesystem::path(map->l_name);
  if (ec || file.empty()) return {};
  return std::filesystem::absolute(file, ec).parent_path();
}

}  // namespace

std::filesystem::path Robot::models_dir() {
  if (const char* env = std::getenv("MJARM_MODELS"); env != nullptr && *env != '\0') return env;
  std::error_code ec;
  std::filesystem::path beside;  // the first candidate beside the binary: named when none exists
  if (const std::filesystem::path folder = folder_of_this_binary(); !folder.empty()) {
    std::string_view relatives = MJARM_MODELS_RELATIVE_DIRS;
    while (!relatives.empty()) {
      const std::size_t colon = relatives.find(':');
      const std::filesystem::path candidate =
          (folder / relatives.substr(0, colon)).lexically_normal();
      if (std::filesystem::is_directory(candidate, ec)) return candidate;
      if (beside.empty()) beside = candidate;
      relatives = colon == std::string_view::npos ? std::string_view() : relatives.substr(colon + 1);
    }
  }
  const std::filesystem::path source = MJARM_MODELS_SOURCE_DIR;
  if (!source.empty() && std::filesystem::is_directory(source, ec)) return source;
  const std::filesystem::path installed = MJARM_MODELS_INSTALL_DIR;
  return installed.empty() ? beside : installed;
}

}  // namespace mjarm
