#pragma once
// Helpers shared by the model tests: load MJCF text with MuJoCo itself, from memory.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <memory>
#include <string>

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
  mj_addBufferVFS(vfs.get(), name, xml.data(), static_cast<int>(xml.size()));
  char err[1024] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), err, sizeof(err));
  mj_deleteVFS(vfs.get());
  if (error) *error = err;
  return ModelPtr(m);
}

}  // namespace mjarm::mjcf_test
