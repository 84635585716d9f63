#pragma once
/// @file
/// `PassiveWebViewer`: the passive viewer's form for machines without a display. Your loop steps
/// the data and calls `sync()`; every browser connected to `url()` sees the model move on the
/// page of `mjarm view --web` (the replay page's scene in live mode, without the panel). `sync()`
/// copies the poses into the server's frame slot and returns: it never waits for a browser (see
/// `LiveServer`).
///
/// The frame is the web viewer's (web_viewer.hpp) without the panel's part: little-endian float32,
/// the data's time, then every body's position (3 per body, the world's first) and every body's
/// quaternion w, x, y, z (4 per body), in body id order.

#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>
#include <string>

#include "mjarm/model/robot.hpp"
#include "mjarm/web/live_server.hpp"

namespace mjarm {

class WebFrame;

class PassiveWebViewer {
 public:
  /// Starts serving @p robot's bodies as @p data holds them (it must outlive the viewer).
  /// @throws Error when @p data is not of @p robot's model size, when the build holds no page
  ///         (MJARM_WEB: the message says how to get it), or as `LiveServer`
  PassiveWebViewer(const Robot& robot, const mjData& data, const LiveServerOptions& options = {});
  ~PassiveWebViewer();
  PassiveWebViewer(const PassiveWebViewer&) = delete;
  PassiveWebViewer& operator=(const PassiveWebViewer&) = delete;

  /// Publishes the data's time and body poses (xpos, xquat: what the last mj_kinematics, mj_step
  /// or mj_forward computed). Allocates nothing after the first call; nothing once closed.
  void sync();
  /// Stops serving (the browsers are disconnected).
  void close() noexcept { server_.reset(); }
  bool running() const noexcept { return server_ != nullptr; }
  /// The page's address (with the token when one is needed); empty once closed.
  std::string url() const { return server_ ? server_->url() : std::string(); }
  /// What the server did (zeros once closed).
  LiveServerStats stats() const { return server_ ? server_->stats() : LiveServerStats{}; }
  std::int64_t syncs() const noexcept { return syncs_; }

 private:
  Robot robot_;
  const mjData& data_;
  std::unique_ptr<LiveServer> server_;
  std::unique_ptr<WebFrame> frame_;
  std::int64_t syncs_ = 0;
};

}  // namespace mjarm
