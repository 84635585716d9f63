#include "mjarm/teleop/passive_web_viewer.hpp"

#include <nlohmann/json.hpp>

#include "mjarm/error.hpp"
#include "mjarm/web/live_page.hpp"
#include "teleop/web_frame.hpp"

namespace mjarm {

namespace {

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
      frame_(std::make_unique<WebFrame>(robot.model(), false)) {
  server_ = std::make_unique<LiveServer>(live_page_html("passive web viewer"), options);
  nlohmann::json greeting = web_greeting(robot_, *frame_);
  greeting["sliders"] = nlohmann::json::array();  // watched, not steered: no panel
  greeting["modes"] = nlohmann::json::array();
  server_->set_greeting(greeting.dump());
}

PassiveWebViewer::~PassiveWebViewer() = default;

void PassiveWebViewer::sync() {
  if (!server_) return;
  frame_->set_bodies(data_.time, data_);
  server_->publish(frame_->bytes());
  ++syncs_;
}

}  // namespace mjarm
