// Whether this build can write a replay page, said before a run that will write one.
#include "mjarm/web/replay_html.hpp"
#include "replay_bundle.hpp"

namespace mjarm {

std::string replay_html_missing() { return web_detail::replay_bundle_missing(); }

}  // namespace mjarm
