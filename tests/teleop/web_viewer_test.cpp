// The viewer in a browser: the browser's messages set the panel (or are refused with the reason,
// the panel unchanged), the greeting describes the frames and sliders, and a browser connected
// to a running web viewer moves the target and sees it move in the streamed frames.

#include "mjarm/teleop/web_viewer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "mjarm/interrupt.hpp"
#include "web/web_client.hpp"

namespace mjarm {
namespace {

using ::testing::HasSubstr;

std::vector<float> floats_of(const std::string& frame) {
  std::vector<float> out(frame.size() / sizeof(float));
  std::memcpy(out.data(), frame.data(), out.size() * sizeof(float));
  return out;
}

TEST(WebViewer, MessagesSetThePanelOrAreRefusedWithTheReason) {
  ViewerSession session(Robot::bundled("panda"));
  PanelState panel = session.initial_panel();
  const double x = panel.target[slider_x] + 0.05;
  EXPECT_EQ(apply_web_message(session, panel,
                              R"({"set": "x", "value": )" + nlohmann::json(x).dump() + "}"),
            "");
  EXPECT_NEAR(panel.target[slider_x], x, 1e-12);
  EXPECT_NEAR(session.stats().X_WT.p.x(), x, 1e-12);
  EXPECT_EQ(apply_web_message(session, panel, R"({"set": "gripper", "value": "0.5"})"), "");
  EXPECT_EQ(panel.gripper, 0.5);
  EXPECT_EQ(apply_web_message(session, panel, R"({"set": "mode", "value": "torque"})"), "");
  EXPECT_EQ(session.mode(), SimulationMode::torque);

  const PanelState before = panel;
  EXPECT_THAT(apply_web_message(session, panel, R"({"set": "x", "value": 99})"), HasSubstr("x"));
  EXPECT_THAT(apply_web_message(session, panel, R"({"set": "elbow", "value": 1})"),
              HasSubstr("elbow"));
  EXPECT_THAT(apply_web_message(session, panel, "not json"), HasSubstr("not a JSON object"));
  EXPECT_THAT(apply_web_message(session, panel, R"({"set": "x"})"), HasSubstr("sets one value"));
  EXPECT_THAT(apply_web_message(session, panel, R"({"set": "x", "value": [1]})"),
              HasSubstr("neither a number nor a string"));
  EXPECT_THAT(apply_web_message(session, panel, R"({"set": "mode", "value": "flying"})"),
              HasSubstr("mode"));
  EXPECT_EQ(std::memcmp(&before, &panel, sizeof(PanelState)), 0);
  EXPECT_EQ(session.mode(), SimulationMode::torque);
}

TEST(WebViewer, TheGreetingDescribesTheFramesAndTheSliders) {
  ViewerSession session(Robot::bundled("panda"));
  const nlohmann::json g =
      nlohmann::json::parse(web_viewer_greeting(session, session.initial_panel()));
  const mjModel& m = session.robot().model();
  ASSERT_EQ(g["bodies"].size(), static_cast<std::size_t>(m.nbody - 1));
  EXPECT_EQ(g["bodies"][0]["parent"], 0);
  EXPECT_EQ(g["sliders"].size(), 7u);
  EXPECT_EQ(g["sliders"][0]["name"], "x");
  EXPECT_LT(g["sliders"][0]["lower"].get<double>(), g["sliders"][0]["value"].get<double>());
  EXPECT_EQ(g["mode"], "kinematic");
  EXPECT_THAT(g["modes"].dump(), HasSubstr("torque"));
  EXPECT_EQ(g["frame"]["header_floats"], 8);
  EXPECT_EQ(g["frame"]["body_floats"], 7);
}

TEST(WebViewer, ABrowserMovesTheTargetAndSeesTheArmFollowInTheFrames) {
  ViewerSession session(Robot::bundled("panda"));
  const double x0 = session.initial_panel().target[slider_x];
  const double x1 = x0 + 0.05;
  const int nbody = session.robot().model().nbody;
  std::thread browser;
  std::vector<float> first, last;
  nlohmann::json greeting;
  const InterruptGuard interrupts;
  WebViewerOptions options;
  const WebViewerReport r = run_web_viewer(session, options, [&](const LiveServer& server) {
    const int port = server.port();
    browser = std::thread([&, port] {
      struct StopTheViewer {
        ~StopTheViewer() { std::raise(SIGINT); }
      } stop;
      test::WebSocketClient client(port, "/ws");
      greeting = nlohmann::json::parse(client.read());
      first = floats_of(client.read());
      client.send(R"({"set": "x", "value": )" + nlohmann::json(x1).dump() + "}");
      // frames until the end effector is within 1 mm of the new target (a hang guard: 20 000)
      for (int k = 0; k < 20000; ++k) {
        last = floats_of(client.read());
        if (std::abs(last[4] - x1) < 1e-6 && std::abs(last[1] - x1) < 1e-3) break;
      }
    });
  });
  browser.join();
  clear_interrupt();
  EXPECT_EQ(r.ended_by, "signal");
  EXPECT_EQ(r.applied, 1);
  EXPECT_EQ(r.refused, 0);
  EXPECT_EQ(greeting["model"], "panda");
  ASSERT_EQ(first.size(), static_cast<std::size_t>(8 + 7 * (nbody - 1)));
  EXPECT_NEAR(first[4], x0, 1e-6);  // the target at start
  ASSERT_EQ(last.size(), first.size());
  EXPECT_NEAR(last[4], x1, 1e-6);
  EXPECT_NEAR(last[1], x1, 1e-3);  // the end effector followed
  EXPECT_GT(last[0], first[0]);    // simulated time went on
  EXPECT_GE(r.server.connections, 1u);
  EXPECT_GT(r.frames, 0);
}

}  // namespace
}  // namespace mjarm
