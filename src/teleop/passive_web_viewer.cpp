#include "mjarm/teleop/passive_web_viewer.hpp"

#include <nlohmann/json.hpp>

#include "mjarm/error.hpp"
#include "teleop/web_viewer_page.hpp"

namespace mjarm {

namespace {

/// What a browser is told on connecting: the bodies in frame order and the frame's layout.
std::string passive_greeting(const Robot& robot) {
  return nlohmann::json{{"model", robot.name()},
                        {"bodies", web_viewer_bodies(robot.model())},
                        {"frame",
                         {{"layout", "float32: time, then per body xyz and quaternion wxyz"},
                          {"header_floats", 1},
                          {"body_floats", 7}}},
                        {"sliders", nlohmann::json::array()},
                        {"modes", nlohmann::json::array()}}
      .dump();
}

const mjData& checked(const Robot& robot, const mjData& data) {
  // a data's arena and buffer sizes come from its model: a mismatch is another model's data,
  // whose bodies would be read out of bounds
  mjData* own = mj_makeData(&robot.model());
  const bool same = own != nullptr && own->narena == data.narena && own->nbuffer == data.nbuffer;
  mj_deleteData(own);
  if (!same)
    throw Error("passive web viewer: the data is not of the model '" + robot.name() +
                "' (its sizes differ)");
  return data;
}

}  // namespace

PassiveWebViewer::PassiveWebViewer(const Robot& robot, const mjData& data,
                                   const LiveServerOptions& options)
    : robot_(robot),
      data_(checked(robot, data)),
      server_(std::make_unique<LiveServer>(web_viewer_page(), options)),
      frame_(static_cast<std::size_t>(1 + 7 * (robot.model().nbody - 1))) {
  server_->set_greeting(passive_greeting(robot_));
}

void PassiveWebViewer::sync() {
  if (!server_) return;
  const int nbody = robot_.model().nbody;
  float* out = frame_.data();
  *out++ = static_cast<float>(data_.time);
  for (int b = 1; b < nbody; ++b) {
    for (int k = 0; k < 3; ++k) *out++ = static_cast<float>(data_.xpos[3 * b + k]);
    for (int k = 0; k < 4; ++k) *out++ = static_cast<float>(data_.xquat[4 * b + k]);
  }
  server_->publish(std::string_view(reinterpret_cast<const char*>(frame_.data()),
                                    frame_.size() * sizeof(float)));
  ++syncs_;
}

}  // namespace mjarm
