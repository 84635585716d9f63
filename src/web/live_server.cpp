#include "mjarm/web/live_server.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <deque>
#include <mutex>
#include <random>
#include <thread>
#include <vector>

#include "mjarm/error.hpp"

namespace mjarm {

namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using boost::system::error_code;

std::string new_token() {
  std::random_device device;
  std::string token;
  for (int word = 0; word < 4; ++word) {
    std::uint32_t bits = device();
    for (int digit = 0; digit < 8; ++digit, bits >>= 4)
      token.push_back("0123456789abcdef"[bits & 15u]);
  }
  return token;
}

/// The value of `token` in a request target's query ("" when it has none).
std::string_view token_in(std::string_view target) {
  const std::size_t question = target.find('?');
  if (question == std::string_view::npos) return {};
  std::string_view query = target.substr(question + 1);
  while (!query.empty()) {
    const std::size_t amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    if (pair.substr(0, 6) == "token=") return pair.substr(6);
    if (amp == std::string_view::npos) break;
    query.remove_prefix(amp + 1);
  }
  return {};
}

std::string_view path_of(std::string_view target) { return target.substr(0, target.find('?')); }

/// Compares without stopping at the first difference (no timing hint about the token).
bool same_secret(std::string_view given, std::string_view secret) noexcept {
  if (given.size() != secret.size()) return false;
  unsigned difference = 0;
  for (std::size_t i = 0; i < secret.size(); ++i)
    difference |= static_cast<unsigned>(given[i] ^ secret[i]);
  return difference == 0;
}

}  // namespace

bool is_loopback_host(std::string_view host) noexcept {
  if (host == "localhost") return true;
  error_code ec;
  const net::ip::address address = net::ip::make_address(std::string(host), ec);
  return !ec && address.is_loopback();
}

struct LiveServer::Impl {
  struct Client;
  struct HttpSession;

  LiveServerOptions options;
  std::string page;
  std::string token;
  std::string host;
  int port = 0;
  net::io_context io{1};  // destroyed last: pending handlers still hold sessions and sockets
  tcp::acceptor acceptor{io};
  net::steady_timer timer{io};
  std::chrono::nanoseconds period{};

  // shared with the caller's threads
  mutable std::mutex mutex;
  std::string latest;  ///< the newest frame
  std::uint64_t latest_seq = 0;
  std::string greeting;
  std::uint64_t greeting_seq = 0;
  std::deque<std::string> inbox;
  LiveServerStats counters;

  // the server thread's own
  std::vector<std::shared_ptr<Client>> clients;
  std::thread thread;

  bool authorized(std::string_view target) const {
    return token.empty() || same_secret(token_in(target), token);
  }
  void count_refused() {
    const std::lock_guard lock(mutex);
    ++counters.refused;
  }
  void deliver(std::string message) {
    const std::lock_guard lock(mutex);
    ++counters.received;
    if (inbox.size() >= options.inbox_messages) {
      inbox.pop_front();
      ++counters.inbox_dropped;
    }
    inbox.push_back(std::move(message));
  }
  void accept();
  void tick();
  void pump(Client& client);
};

/// One WebSocket client: the newest frame is sent when its previous send has finished.
struct LiveServer::Impl::Client : std::enable_shared_from_this<Client> {
  Client(tcp::socket socket, Impl& server) : ws(std::move(socket)), server(server) {}

  websocket::stream<beast::tcp_stream> ws;
  Impl& server;
  http::request<http::string_body> upgrade;
  beast::flat_buffer in;
  std::string out;  // the message being sent (its capacity is kept)
  bool open = false;
  bool writing = false;
  std::uint64_t frame_seq = 0;
  std::uint64_t greeting_seq = 0;

  void start(http::request<http::string_body> request) {
    upgrade = std::move(request);
    websocket::stream_base::timeout timeouts =
        websocket::stream_base::timeout::suggested(beast::role_type::server);
    // a browser answers the pings: a client that does not (stopped, gone) is closed
    timeouts.idle_timeout = std::chrono::seconds(20);
    timeouts.keep_alive_pings = true;
    ws.set_option(timeouts);
    ws.read_message_max(server.options.max_message_bytes);
    beast::get_lowest_layer(ws).expires_never();
    ws.async_accept(upgrade, [self = shared_from_this()](error_code ec) {
      if (ec) return;
      self->open = true;
      {
        const std::lock_guard lock(self->server.mutex);
        self->frame_seq = self->server.latest_seq;  // what came before is not skipped
        ++self->server.counters.connections;
      }
      self->server.clients.push_back(self);
      self->read();
      self->server.pump(*self);
    });
  }

  void read() {
    ws.async_read(in, [self = shared_from_this()](error_code ec, std::size_t) {
      if (ec) {
        self->close();
        return;
      }
      if (self->ws.got_text()) self->server.deliver(beast::buffers_to_string(self->in.data()));
      self->in.consume(self->in.size());
      self->read();
    });
  }

  void close() {
    if (!open) return;
    open = false;
    error_code ignored;
    beast::get_lowest_layer(ws).socket().close(ignored);
  }
};

/// One HTTP request: the page, or the upgrade of `/ws` to a WebSocket client.
struct LiveServer::Impl::HttpSession : std::enable_shared_from_this<HttpSession> {
  HttpSession(tcp::socket socket, Impl& server) : stream(std::move(socket)), server(server) {}

  beast::tcp_stream stream;
  Impl& server;
  beast::flat_buffer buffer;
  http::request_parser<http::string_body> parser;
  http::response<http::string_body> response;

  void start() {
    parser.header_limit(8192);
    parser.body_limit(1024);
    stream.expires_after(std::chrono::seconds(10));
    http::async_read(stream, buffer, parser,
                     [self = shared_from_this()](error_code ec, std::size_t) {
                       if (!ec) self->answer();
                     });
  }

  void answer() {
    http::request<http::string_body>& request = parser.get();
    const std::string_view target(request.target().data(), request.target().size());
    if (!server.authorized(target)) {
      server.count_refused();
      respond(request, http::status::forbidden,
              "mjarm live view: this address needs the access token printed at start "
              "(?token=...)\n");
      return;
    }
    const std::string_view path = path_of(target);
    if (websocket::is_upgrade(request)) {
      if (path != "/ws") {
        respond(request, http::status::not_found, "mjarm live view: the stream is at /ws\n");
        return;
      }
      if (server.clients.size() >= server.options.max_clients) {
        server.count_refused();
        respond(request, http::status::service_unavailable, "mjarm live view: too many clients\n");
        return;
      }
      stream.expires_never();
      std::make_shared<Client>(stream.release_socket(), server)->start(parser.release());
      return;
    }
    if (request.method() != http::verb::get && request.method() != http::verb::head) {
      respond(request, http::status::method_not_allowed, "mjarm live view: GET only\n");
      return;
    }
    if (path != "/" && path != "/index.html") {
      respond(request, http::status::not_found, "mjarm live view: the page is at /\n");
      return;
    }
    {
      const std::lock_guard lock(server.mutex);
      ++server.counters.pages;
    }
    respond(request, http::status::ok, server.page, "text/html; charset=utf-8");
  }

  void respond(const http::request<http::string_body>& request, http::status status,
               std::string body, const char* type = "text/plain; charset=utf-8") {
    response.version(request.version());
    response.result(status);
    response.set(http::field::content_type, type);
    response.set(http::field::cache_control, "no-store");
    if (request.method() != http::verb::head) response.body() = std::move(body);
    response.keep_alive(false);
    response.prepare_payload();
    http::async_write(stream, response, [self = shared_from_this()](error_code, std::size_t) {
      error_code ignored;
      self->stream.socket().shutdown(tcp::socket::shutdown_send, ignored);
    });
  }
};

void LiveServer::Impl::accept() {
  acceptor.async_accept([this](error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec) std::make_shared<HttpSession>(std::move(socket), *this)->start();
    accept();
  });
}

void LiveServer::Impl::tick() {
  std::erase_if(clients, [](const std::shared_ptr<Client>& c) { return !c->open; });
  {
    const std::lock_guard lock(mutex);
    counters.clients = clients.size();
  }
  for (const std::shared_ptr<Client>& client : clients) pump(*client);
  timer.expires_after(period);
  timer.async_wait([this](error_code ec) {
    if (!ec) tick();
  });
}

void LiveServer::Impl::pump(Client& client) {
  if (!client.open || client.writing) return;
  bool text = false;
  {
    const std::lock_guard lock(mutex);
    if (client.greeting_seq != greeting_seq) {
      client.out.assign(greeting);
      client.greeting_seq = greeting_seq;
      text = true;
    } else if (client.frame_seq != latest_seq) {
      counters.skipped += latest_seq - client.frame_seq - 1;
      client.out.assign(latest);
      client.frame_seq = latest_seq;
    } else {
      return;
    }
  }
  client.writing = true;
  client.ws.text(text);
  client.ws.async_write(net::buffer(client.out),
                        [self = client.shared_from_this()](error_code ec, std::size_t) {
                          self->writing = false;
                          if (ec) {
                            self->close();
                            return;
                          }
                          const std::lock_guard lock(self->server.mutex);
                          ++self->server.counters.sent;
                        });
}

LiveServer::LiveServer(std::string page, const LiveServerOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_fields(options);
  Impl& s = *impl_;
  s.options = options;
  s.page = std::move(page);
  s.host = options.host == "localhost" ? "127.0.0.1" : options.host;
  error_code ec;
  const net::ip::address address = net::ip::make_address(s.host, ec);
  if (ec)
    throw Error("live server: '" + options.host + "' is not an IP address (" + ec.message() +
                "); 127.0.0.1 listens on this machine only, 0.0.0.0 on every interface");
  if (options.require_token || !address.is_loopback()) s.token = new_token();
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(options.port));
  const auto fail = [&](const char* what) {
    const bool taken = ec == net::error::address_in_use;
    throw Error("live server: cannot " + std::string(what) + " " + s.host + ":" +
                std::to_string(options.port) + ": " + ec.message() +
                (taken ? " (another program, or another mjarm view, listens there: choose "
                         "another --port, or 0 for a free one)"
                       : ""));
  };
  if (s.acceptor.open(endpoint.protocol(), ec)) fail("open a socket for");
  if (s.acceptor.set_option(net::socket_base::reuse_address(true), ec)) fail("reuse");
  if (s.acceptor.bind(endpoint, ec)) fail("listen on");
  if (s.acceptor.listen(net::socket_base::max_listen_connections, ec)) fail("listen on");
  s.port = s.acceptor.local_endpoint().port();
  s.period = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(1.0 / options.send_rate));
  s.accept();
  s.tick();
  s.thread = std::thread([&s] { s.io.run(); });
}

LiveServer::~LiveServer() {
  impl_->io.stop();
  impl_->thread.join();
}

int LiveServer::port() const noexcept { return impl_->port; }

const std::string& LiveServer::token() const noexcept { return impl_->token; }

std::string LiveServer::url() const {
  const bool v6 = impl_->host.find(':') != std::string::npos;
  std::string url = "http://" + (v6 ? "[" + impl_->host + "]" : impl_->host) + ":" +
                    std::to_string(impl_->port) + "/";
  if (!impl_->token.empty()) url += "?token=" + impl_->token;
  return url;
}

void LiveServer::publish(std::string_view frame) {
  const std::lock_guard lock(impl_->mutex);
  impl_->latest.assign(frame);
  ++impl_->latest_seq;
  ++impl_->counters.published;
}

void LiveServer::set_greeting(std::string text) {
  const std::lock_guard lock(impl_->mutex);
  impl_->greeting = std::move(text);
  ++impl_->greeting_seq;
}

bool LiveServer::poll(std::string& message) {
  const std::lock_guard lock(impl_->mutex);
  if (impl_->inbox.empty()) return false;
  message.swap(impl_->inbox.front());
  impl_->inbox.pop_front();
  return true;
}

LiveServerStats LiveServer::stats() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->counters;
}

}  // namespace mjarm
