// The pages' shared head and escaping (mjarm/web/page_html.hpp): the replay, the live view and the
// sweep dashboard write their JSON and titles through it.

#include "mjarm/web/page_html.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace {

TEST(PageHtml, JsonInAScriptElementCannotCloseItAndReadsBackTheSame) {
  const nlohmann::json data = {{"message", "</script><script>alert(1)</script>"},
                               {"note", "a < b"}};
  const std::string safe = mjarm::script_safe_json(data.dump());
  EXPECT_EQ(safe.find('<'), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(safe), data);
}

TEST(PageHtml, TextIsEscapedForAnElementAndAnAttribute) {
  EXPECT_EQ(mjarm::html_text("a <b> & \"c\""), "a &lt;b&gt; &amp; &quot;c&quot;");
  const std::string head = mjarm::html_page_head("x </title> y");
  EXPECT_NE(head.find("<title>x &lt;/title&gt; y</title>"), std::string::npos);
  EXPECT_EQ(head.find("</title> y"), std::string::npos);
}

}  // namespace
