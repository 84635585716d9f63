// The viewer in a browser: the browser's messages set the panel (or are refused with the reason,
// the panel unchanged), the greeting describes the model as the replay page draws it, the frames
// and the sliders, a frame holds the session's poses, and a browser connected to a running web
// viewer moves the target and sees it move in the streamed frames. A build without the page
// (MJARM_WEB) refuses to serve, saying how to get it.

#include "mjarm/teleop/web_viewer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "mjarm/interrupt.hpp"
#include "mjarm/lie/rotation.hpp"
#include "mjarm/web/replay_html.hpp"
#include "teleop/web_frame.hpp"
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

TEST(WebViewer, TheGreetingDescribesTheModelTheFramesAndTheSliders) {
  ViewerSession session(Robot::bundled("panda"));
  const nlohmann::json g =
      nlohmann::json::parse(web_viewer_greeting(session, session.initial_panel()));
  const mjModel& m = session.robot().model();
  // the model as a replay file describes it: every body (the world first), the drawn geoms
  ASSERT_EQ(g["bodies"].size(), static_cast<std::size_t>(m.nbody));
  EXPECT_EQ(g["bodies"][1]["parent"], 0);
  EXPECT_GT(g["geoms"].size(), 0u);
  for (const nlohmann::json& geom : g["geoms"]) EXPECT_LT(geom["body"].get<int>(), m.nbody);
  EXPECT_EQ(g["cameras"].size(), static_cast<std::size_t>(m.ncam));
  EXPECT_EQ(g["model"], "panda");
  EXPECT_EQ(g["sliders"].size(), 7u);
  EXPECT_EQ(g["sliders"][0]["name"], "x");
  EXPECT_LT(g["sliders"][0]["lower"].get<double>(), g["sliders"][0]["value"].get<double>());
  EXPECT_EQ(g["mode"], "kinematic");
  EXPECT_THAT(g["modes"].dump(), HasSubstr("torque"));
  const nlohmann::json& f = g["frame"];
  EXPECT_EQ(f["time"], 0);
  EXPECT_EQ(f["tool"], 1);
  EXPECT_EQ(f["target"], 8);
  EXPECT_EQ(f["gripper"], 15);
  EXPECT_EQ(f["pos"], 16);
  EXPECT_EQ(f["quat"], 16 + 3 * m.nbody);
  EXPECT_EQ(f["floats"], 16 + 7 * m.nbody);
  EXPECT_EQ(f["bodies"], m.nbody);
}

TEST(WebViewer, AFrameHoldsTheSessionsPoses) {
  ViewerSession session(Robot::bundled("panda"));
  session.step(50);
  const mjModel& m = session.robot().model();
  const mjData& d = session.simulation().data();
  const ViewerStats& s = session.stats();
  WebFrame frame(m, true);
  frame.set_bodies(s.time, d);
  frame.set_panel(s.X_WE, s.X_WT, 0.25);
  const std::vector<float> f = floats_of(std::string(frame.bytes()));
  ASSERT_EQ(f.size(), static_cast<std::size_t>(16 + 7 * m.nbody));
  EXPECT_FLOAT_EQ(f[0], static_cast<float>(s.time));
  EXPECT_GT(f[0], 0.0f);
  const Eigen::Vector4d q_tool = quaternion_from_rotation(s.X_WE.R);
  for (int k = 0; k < 3; ++k) {
    EXPECT_FLOAT_EQ(f[1 + k], static_cast<float>(s.X_WE.p[k]));
    EXPECT_FLOAT_EQ(f[8 + k], static_cast<float>(s.X_WT.p[k]));
  }
  for (int k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(f[4 + k], static_cast<float>(q_tool[k]));
  EXPECT_FLOAT_EQ(f[15], 0.25f);
  const int quat = 16 + 3 * m.nbody;
  for (int b = 0; b < m.nbody; ++b) {
    for (int k = 0; k < 3; ++k)
      EXPECT_FLOAT_EQ(f[static_cast<std::size_t>(16 + 3 * b + k)],
                      static_cast<float>(d.xpos[3 * b + k]));
    for (int k = 0; k < 4; ++k)
      EXPECT_FLOAT_EQ(f[static_cast<std::size_t>(quat + 4 * b + k)],
                      static_cast<float>(d.xquat[4 * b + k]));
  }
  // without the panel: the time, then the bodies
  WebFrame bodies(m, false);
  bodies.set_bodies(s.time, d);
  bodies.set_panel(s.X_WE, s.X_WT, 1.0);  // no room for it: unchanged
  const std::vector<float> b = floats_of(std::string(bodies.bytes()));
  ASSERT_EQ(b.size(), static_cast<std::size_t>(1 + 7 * m.nbody));
  EXPECT_EQ(bodies.layout()["pos"], 1);
  EXPECT_FALSE(bodies.layout().contains("tool"));
  EXPECT_FLOAT_EQ(b[1 + 3 * (m.nbody - 1) + 2], static_cast<float>(d.xpos[3 * (m.nbody - 1) + 2]));
}

TEST(WebViewer, ABrowserMovesTheTargetAndSeesTheArmFollowInTheFrames) {
  ViewerSession session(Robot::bundled("panda"));
  if (!replay_html_available()) {
    // a build without the page (MJARM_WEB) serves nothing and says how to get it
    try {
      run_web_viewer(session, WebViewerOptions{}, nullptr);
      ADD_FAILURE() << "served without a page";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("view --web: this mjarm was built without the replay page"));
      EXPECT_THAT(e.what(), HasSubstr("-DMJARM_WEB=ON"));
    }
    return;
  }
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
      // frames until the end effector (the tool) is within 1 mm of the new target (a hang
      // guard: 20 000)
      for (int k = 0; k < 20000; ++k) {
        last = floats_of(client.read());
        if (std::abs(last[8] - x1) < 1e-6 && std::abs(last[1] - x1) < 1e-3) break;
      }
    });
  });
  browser.join();
  clear_interrupt();
  EXPECT_EQ(r.ended_by, "signal");
  EXPECT_EQ(r.applied, 1);
  EXPECT_EQ(r.refused, 0);
  EXPECT_EQ(greeting["model"], "panda");
  ASSERT_EQ(first.size(), static_cast<std::size_t>(16 + 7 * nbody));
  EXPECT_EQ(greeting["frame"]["floats"], first.size());
  EXPECT_NEAR(first[8], x0, 1e-6);  // the target at start
  ASSERT_EQ(last.size(), first.size());
  EXPECT_NEAR(last[8], x1, 1e-6);
  EXPECT_NEAR(last[1], x1, 1e-3);  // the end effector followed
  EXPECT_GT(last[0], first[0]);    // simulated time went on
  EXPECT_GE(r.server.connections, 1u);
  EXPECT_GT(r.frames, 0);
}

}  // namespace
}  // namespace mjarm
