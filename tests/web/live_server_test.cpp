// The live server: the page, the access token, the stream of the newest frame, messages back,
// bounded inbox and message size, a stalled client that costs nobody else anything, bad options.

#include "mjarm/web/live_server.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/system/system_error.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/cli_runner.hpp"
#include "mjarm/error.hpp"
#include "support/error_message.hpp"
#include "web/web_client.hpp"

namespace mjarm {
namespace {

using test::http_get;
using test::WebSocketClient;
using ::testing::HasSubstr;

/// Waits until @p done: the server's thread makes it true (a hang ends at CTest's timeout).
template <typename Predicate>
bool eventually(Predicate done) {
  while (!done()) std::this_thread::yield();
  return true;
}

TEST(LiveServer, ServesThePageOnLoopbackWithoutAToken) {
  LiveServer server("<p>page</p>");
  EXPECT_TRUE(server.token().empty());
  EXPECT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
  EXPECT_EQ(http_get(server.port(), "/"), std::make_pair(200, std::string("<p>page</p>")));
  EXPECT_EQ(http_get(server.port(), "/index.html").first, 200);
  EXPECT_EQ(http_get(server.port(), "/other").first, 404);
  EXPECT_EQ(server.stats().pages, 2u);
}

TEST(LiveServer, WithATokenEveryRequestWithoutItOrWithAnotherIsRefused) {
  LiveServerOptions options;
  options.require_token = true;
  LiveServer server("<p>page</p>", options);
  const std::string token = server.token();
  ASSERT_EQ(token.size(), 32u);
  EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_THAT(server.url(), HasSubstr("/?token=" + token));
  EXPECT_EQ(http_get(server.port(), "/").first, 403);
  EXPECT_EQ(http_get(server.port(), "/?token=0123").first, 403);
  std::string wrong = token;
  wrong[31] = wrong[31] == 'a' ? 'b' : 'a';
  EXPECT_EQ(http_get(server.port(), "/?token=" + wrong).first, 403);
  EXPECT_THAT(http_get(server.port(), "/?token=" + wrong).second, HasSubstr("access token"));
  EXPECT_EQ(http_get(server.port(), "/?x=1&token=" + token).first, 200);
  EXPECT_THROW(WebSocketClient(server.port(), "/ws?token=" + wrong), boost::system::system_error);
  EXPECT_THROW(WebSocketClient(server.port(), "/ws"), boost::system::system_error);
  WebSocketClient client(server.port(), "/ws?token=" + token);
  EXPECT_TRUE(eventually([&] { return server.stats().connections == 1; }));
  EXPECT_EQ(server.stats().refused, 6u);
  // another interface than loopback always needs one
  LiveServerOptions open;
  open.host = "0.0.0.0";
  LiveServer everywhere("<p>page</p>", open);
  EXPECT_EQ(everywhere.token().size(), 32u);
  EXPECT_NE(everywhere.token(), token);
  EXPECT_EQ(http_get(everywhere.port(), "/").first, 403);
}

TEST(LiveServer, AClientGetsTheGreetingThenTheNewestFrameAndItsMessagesArePolled) {
  LiveServer server("page");
  server.set_greeting(R"({"model": "m"})");
  WebSocketClient client(server.port(), "/ws");
  bool text = false;
  EXPECT_EQ(client.read(&text), R"({"model": "m"})");
  EXPECT_TRUE(text);
  server.publish("frame 1");
  EXPECT_EQ(client.read(&text), "frame 1");
  EXPECT_FALSE(text);  // frames are binary
  client.send(R"({"set": "x", "value": 0.4})");
  std::string message;
  ASSERT_TRUE(eventually([&] { return server.poll(message); }));
  EXPECT_EQ(message, R"({"set": "x", "value": 0.4})");
  EXPECT_FALSE(server.poll(message));
  // a new greeting reaches the clients connected
  server.set_greeting("second");
  EXPECT_EQ(client.read(&text), "second");
  EXPECT_TRUE(text);
  const LiveServerStats s = server.stats();
  EXPECT_EQ(s.connections, 1u);
  EXPECT_EQ(s.published, 1u);
  EXPECT_EQ(s.received, 1u);
}

TEST(LiveServer, TwoBrowsersEachGetTheGreetingAndEveryFrameAndBothAreHeard) {
  LiveServer server("page");
  server.set_greeting("hello");
  std::optional<WebSocketClient> first;
  first.emplace(server.port(), "/ws");
  WebSocketClient second(server.port(), "/ws");
  EXPECT_EQ(first->read(), "hello");
  EXPECT_EQ(second.read(), "hello");
  ASSERT_TRUE(eventually([&] { return server.stats().clients == 2; }));
  for (int k = 0; k < 3; ++k) {
    server.publish("frame " + std::to_string(k));
    // each reads before the next is published: none is skipped for a client that keeps up
    EXPECT_EQ(first->read(), "frame " + std::to_string(k));
    EXPECT_EQ(second.read(), "frame " + std::to_string(k));
  }
  first->send("from the first");
  second.send("from the second");
  ASSERT_TRUE(eventually([&] { return server.stats().received == 2; }));
  std::vector<std::string> messages(2);
  ASSERT_TRUE(server.poll(messages[0]));
  ASSERT_TRUE(server.poll(messages[1]));
  std::sort(messages.begin(), messages.end());
  EXPECT_EQ(messages, (std::vector<std::string>{"from the first", "from the second"}));
  // one leaves: the other is still served
  first.reset();
  ASSERT_TRUE(eventually([&] { return server.stats().clients == 1; }));
  server.publish("after");
  EXPECT_EQ(second.read(), "after");
  EXPECT_EQ(server.stats().connections, 2u);
}

TEST(LiveServer, AStalledClientNeitherBlocksThePublisherNorTheOtherClients) {
  LiveServerOptions options;
  options.send_rate = 1000.0;
  LiveServer server("page", options);
  WebSocketClient stalled(server.port(), "/ws");  // never reads
  stalled.shrink_receive_buffer();
  WebSocketClient healthy(server.port(), "/ws");
  ASSERT_TRUE(eventually([&] { return server.stats().clients == 2; }));
  // 64 KiB frames: a few fill the stalled client's socket buffers, after which the server holds
  // its one frame in flight and skips the rest for it
  std::string frame(64 * 1024, 'x');
  constexpr int kFrames = 600;
  for (int k = 0; k < kFrames; ++k) {
    const std::string id = std::to_string(k);
    frame.replace(0, id.size(), id);
    frame[id.size()] = ';';
    server.publish(frame);  // returns at once: the test would hang here otherwise
    if (k % 20 == 0) healthy.read();  // paced by the reading client's frames, not a clock
  }
  // the healthy client gets the newest frame even though the other has stopped reading
  std::string got;
  while (got.substr(0, got.find(';')) != std::to_string(kFrames - 1)) got = healthy.read();
  const LiveServerStats s = server.stats();
  EXPECT_EQ(s.published, static_cast<std::uint64_t>(kFrames));
  // the stalled client got at most what its buffers took; the rest were skipped for it, not kept
  EXPECT_LT(s.sent, static_cast<std::uint64_t>(2 * kFrames));
  EXPECT_GT(s.skipped, static_cast<std::uint64_t>(kFrames / 2));
}

TEST(LiveServer, TheInboxKeepsTheNewestMessagesAndALongMessageClosesItsClient) {
  LiveServerOptions options;
  options.inbox_messages = 4;
  options.max_message_bytes = 64;
  LiveServer server("page", options);
  WebSocketClient client(server.port(), "/ws");
  for (int k = 0; k < 10; ++k) client.send("m" + std::to_string(k));
  ASSERT_TRUE(eventually([&] { return server.stats().received == 10; }));
  std::string message;
  for (int k = 6; k < 10; ++k) {
    ASSERT_TRUE(server.poll(message));
    EXPECT_EQ(message, "m" + std::to_string(k));
  }
  EXPECT_FALSE(server.poll(message));
  EXPECT_EQ(server.stats().inbox_dropped, 6u);
  client.send(std::string(65, 'y'));
  EXPECT_THROW(client.read(), boost::system::system_error);  // closed by the server
  EXPECT_EQ(server.stats().received, 10u);
}

TEST(LiveServer, BadOptionsAreRefusedWithTheirReason) {
  LiveServerOptions options;
  options.host = "not-an-address";
  EXPECT_THAT(test::error_of([&] { LiveServer server("page", options); }),
              HasSubstr("'not-an-address' is not an IP address"));
  options.host = "127.0.0.1";
  options.port = 70000;
  EXPECT_THAT(test::error_of([&] { LiveServer server("page", options); }), HasSubstr("port"));
  options.port = 0;
  options.send_rate = 0.0;
  EXPECT_THAT(test::error_of([&] { LiveServer server("page", options); }), HasSubstr("send_rate"));
  LiveServer first("page");
  LiveServerOptions taken;
  taken.port = first.port();
  EXPECT_THAT(test::error_of([&] { LiveServer second("page", taken); }),
              HasSubstr("cannot listen on 127.0.0.1:" + std::to_string(first.port())));
  EXPECT_THAT(test::error_of([&] { LiveServer second("page", taken); }),
              HasSubstr("choose another --port"));
  EXPECT_TRUE(is_loopback_host("localhost"));
  EXPECT_TRUE(is_loopback_host("127.0.0.2"));
  EXPECT_TRUE(is_loopback_host("::1"));
  EXPECT_FALSE(is_loopback_host("0.0.0.0"));
  EXPECT_FALSE(is_loopback_host("garbage"));
}

TEST(LiveServer, TheWebViewOnAPortInUseIsAClearError) {
  LiveServer holder("page");  // holds the port
  const std::string port = std::to_string(holder.port());
  const test::CliRun run =
      test::run_cli({"view", "planar2", "--web", "--port", port, "--duration", "5"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_THAT(run.err, HasSubstr("cannot listen on 127.0.0.1:" + port));
  EXPECT_THAT(run.err, HasSubstr("choose another --port"));
}

}  // namespace
}  // namespace mjarm
