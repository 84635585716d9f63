#include "mjarm/model/mujoco_library.hpp"

#include <dlfcn.h>
#include <mujoco/mujoco.h>

#include "mjarm/error.hpp"

namespace mjarm {

std::string mujoco_version_text(int version) {
  return std::to_string(version / 1000000) + "." + std::to_string(version / 1000 % 1000) + "." +
         std::to_string(version % 1000);
}

std::filesystem::path mujoco_library_path() {
  // the version string lives in the library's own data: unlike a function's address, which in
  // an executable may be a stub of the executable's, it always belongs to the library
  Dl_info info;
  if (dladdr(static_cast<const void*>(mj_versionString()), &info) == 0 || info.dli_fname == nullptr)
    return {};
  return info.dli_fname;
}

void check_mujoco_library() {
  const int library = mj_version();
  if (library == mjVERSION_HEADER) return;
  const std::filesystem::path path = mujoco_library_path();
  throw Error("the MuJoCo library loaded is version " + mujoco_version_text(library) + " (" +
              (path.empty() ? std::string("file unknown") : path.string()) +
              ") but mjarm was compiled with MuJoCo " + mujoco_version_text(mjVERSION_HEADER) +
              "'s headers; run mjarm with MuJoCo " + mujoco_version_text(mjVERSION_HEADER) +
              " (pip install mujoco==" + mujoco_version_text(mjVERSION_HEADER) +
              " in its virtual environment) or rebuild mjarm against the library you have");
}

}  // namespace mjarm
