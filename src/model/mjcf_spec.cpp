#include "mjarm/model/mjcf_spec.hpp"

#include <mutex>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/model/user_file.hpp"
#include "mjcf_staging.hpp"
#include "mujoco_loading.hpp"

namespace mjarm {

SpecPtr parse_mjcf_file(const std::filesystem::path& path, std::vector<std::string>* warnings) {
  install_mujoco_handlers();
  const std::string text = read_user_file(path, "model file");
  const StagedMjcf staged = stage_mjcf(text, std::filesystem::absolute(path).parent_path(), path);
  char error[1024] = "";
  std::vector<std::string> messages;
  mjSpec* spec = nullptr;
  {
    const std::lock_guard<std::mutex> guard(model_detail::xml_loader_mutex());
    const model_detail::LoadWarnings capture(messages);
    spec = mj_parseXMLString(staged.xml.c_str(), nullptr, error, sizeof(error));
  }
  if (spec == nullptr)
    throw Error("cannot load '" + path.string() + "': " + staged.to_source_lines(error));
  model_detail::add_load_message(messages, error, staged.to_source_lines(error));
  if (warnings != nullptr) warnings->insert(warnings->end(), messages.begin(), messages.end());
  return SpecPtr(spec);
}

}  // namespace mjarm
