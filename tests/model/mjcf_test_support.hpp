#pragma once
// Helpers shared by the MJCF translator tests: load MJCF text with MuJoCo 2.2.2 from memory.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace mjarm::mjcf_test {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// Compiles MJCF text with the installed MuJoCo (from an in-memory file); null on failure, with
/// MuJoCo's message in `error`.
inline ModelPtr load_xml(const std::string& xml, std::string* error = nullptr) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "mjcf_test_model.xml";
  mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size()));
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], xml.data(), xml.size());
  char err[1024] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), err, sizeof(err));
  mj_deleteVFS(vfs.get());
  if (error) *error = err;
  return ModelPtr(m);
}

/// Number of warnings that contain `needle`.
inline int count_containing(const std::vector<std::string>& warnings, const std::string& needle) {
  return static_cast<int>(std::count_if(warnings.begin(), warnings.end(), [&](const auto& w) {
    return w.find(needle) != std::string::npos;
  }));
}

}  // namespace mjarm::mjcf_test
