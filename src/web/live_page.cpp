#include "mjarm/web/live_page.hpp"

#include "mjarm/error.hpp"
#include "mjarm/web/page_html.hpp"
#include "replay_bundle.hpp"
#include "replay_scene.hpp"

namespace mjarm {

std::string live_page_html(std::string_view who) {
  const std::string missing = web_detail::replay_bundle_missing();
  if (!missing.empty()) throw Error(std::string(who) + ": " + missing);
  // an empty icon: a browser asks the server for no favicon (a 404 in its console); the empty
  // block marks live mode: the script takes its data from the server's greeting
  return html_page_head("mjarm live view", "<link rel=\"icon\" href=\"data:,\">\n") +
         "<script type=\"application/json\" id=\"mjarm-live\">{}</script>\n<script>" +
         web_detail::replay_bundle() + "</script>\n</body>\n</html>\n";
}

nlohmann::json live_scene(const mjModel& m) { return web_detail::replay_scene(m).json; }

}  // namespace mjarm
