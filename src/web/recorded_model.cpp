#include "mjarm/web/recorded_model.hpp"

#include <memory>
#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/user_file.hpp"

namespace mjarm {

Robot load_mjb_model(const std::filesystem::path& path) {
  const std::string bytes = read_user_file(path, "binary model", kMaxDataFileBytes);
  mjModel* model = mj_loadModelBuffer(bytes.data(), static_cast<mjtSize>(bytes.size()));
  if (model == nullptr) {
    throw Error("MuJoCo could not load the binary model '" + path.string() +
                "' (written by another MuJoCo version, or damaged)");
  }
  return Robot::from_model(
      std::shared_ptr<const mjModel>(
          model, [](const mjModel* p) { mj_deleteModel(const_cast<mjModel*>(p)); }),
      path.string());
}

Robot recorded_model(const plot::Recording& recording) {
  const std::filesystem::path path = recording.directory() / "model.mjb";
  if (!std::filesystem::exists(path)) {
    throw Error("replay-html: the recording '" + recording.directory().string() +
                "' holds no model.mjb (recorded before mjarm kept the model): name the model it "
                "was recorded on with --model");
  }
  return load_mjb_model(path);
}

}  // namespace mjarm
