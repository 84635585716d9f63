// The live view's page: the replay page's script in live mode, or, in a build without the page
// (MJARM_WEB), a refusal in replay-html's words that says how to get it.

#include "mjarm/web/live_page.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mjarm/error.hpp"
#include "mjarm/model/robot.hpp"
#include "mjarm/web/replay_html.hpp"

namespace mjarm {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(LivePage, IsTheReplayPagesScriptInLiveModeOrARefusalThatSaysHowToGetIt) {
  if (!replay_html_available()) {
    try {
      live_page_html("view --web");
      ADD_FAILURE() << "a page without its script";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("view --web: this mjarm was built without the replay page"));
      EXPECT_THAT(e.what(), HasSubstr("-DMJARM_WEB=ON"));
    }
    return;
  }
  const std::string page = live_page_html("view --web");
  EXPECT_THAT(page, HasSubstr("<title>mjarm live view</title>"));
  EXPECT_THAT(page, HasSubstr("<link rel=\"icon\" href=\"data:,\">"));  // no favicon request
  EXPECT_THAT(page, HasSubstr("<script type=\"application/json\" id=\"mjarm-live\">{}</script>"));
  EXPECT_THAT(page, Not(HasSubstr("<script type=\"application/json\" id=\"mjarm-replay-data\">")));
  // the bundled script: its live view and the three.js it draws with
  EXPECT_THAT(page, HasSubstr("mjarmLive"));
  EXPECT_THAT(page, HasSubstr("WebGLRenderer"));
  EXPECT_GT(page.size(), 100000u);
}

TEST(LivePage, TheSceneDescribesTheModelAsAReplayFileDoes) {
  const Robot robot = Robot::bundled("panda");
  const mjModel& m = robot.model();
  const nlohmann::json scene = live_scene(m);
  ASSERT_EQ(scene["bodies"].size(), static_cast<std::size_t>(m.nbody));
  EXPECT_EQ(scene["bodies"][0]["parent"], 0);
  EXPECT_GT(scene["geoms"].size(), 0u);
  for (const nlohmann::json& g : scene["geoms"]) {
    EXPECT_LT(g["body"].get<int>(), m.nbody);
    if (g["type"] == "mesh") EXPECT_LT(g["mesh"].get<std::size_t>(), scene["meshes"].size());
  }
  EXPECT_EQ(scene["cameras"].size(), static_cast<std::size_t>(m.ncam));
  EXPECT_GT(scene["extent"].get<double>(), 0.0);
}

}  // namespace
}  // namespace mjarm
