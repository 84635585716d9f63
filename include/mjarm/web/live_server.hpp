#pragma once
/// @file
/// `LiveServer`: a small HTTP + WebSocket server (Boost.Beast) for watching and steering a
/// running simulation from a browser on a machine without a display. It serves one page at `/`,
/// streams the latest state frame to every client connected at `/ws`, and hands the clients'
/// text messages (slider moves) to the simulation thread.
///
/// The simulation never waits for a browser: `publish` copies the frame into one slot under a
/// short lock, and the server's own thread sends each client the newest frame when the client's
/// previous send has finished, dropping the frames in between (a stalled client costs one frame
/// buffer, never memory that grows or time on the simulation's side). Incoming messages wait in
/// a bounded inbox (the oldest dropped beyond it).
///
/// Bound to 127.0.0.1 by default (reach it through an SSH tunnel). On any other interface, or
/// when asked, every request must carry the access token generated at start (`?token=…`):
/// requests without it, or with another, are answered 403 and counted.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "mjarm/fields.hpp"

namespace mjarm {

/// Settings of a `LiveServer`.
struct LiveServerOptions {
  std::string host = "127.0.0.1";  ///< interface to listen on (an IPv4 or IPv6 address)
  int port = 0;                    ///< TCP port; 0: a free one (see `LiveServer::port`)
  /// Require the access token even on the loopback interface (it is always required on others).
  bool require_token = false;
  double send_rate = 60.0;               ///< frames sent per second at most [Hz]
  std::size_t inbox_messages = 256;      ///< client messages kept until polled (oldest dropped)
  std::size_t max_message_bytes = 4096;  ///< a longer client message closes its connection
  std::size_t max_clients = 16;          ///< connections beyond are refused (503)
};

constexpr auto declared_fields(const LiveServerOptions*) {
  using S = LiveServerOptions;
  return declare<S>(
      "live server", field("host", &S::host, "interface to listen on"),
      field("port", &S::port, "", Range::closed(0, 65535), "TCP port; 0: a free one"),
      field("require_token", &S::require_token, "require the access token on loopback too"),
      field("send_rate", &S::send_rate, "Hz", Range::closed(1.0, 1000.0),
            "frames sent per second at most"),
      field("inbox_messages", &S::inbox_messages, "", Range::closed(1, 1 << 20),
            "client messages kept until polled"),
      field("max_message_bytes", &S::max_message_bytes, "B", Range::closed(16, 1 << 20),
            "longest client message"),
      field("max_clients", &S::max_clients, "", Range::closed(1, 1024),
            "simultaneous connections"));
}

/// What the server has done so far (all counts since start).
struct LiveServerStats {
  std::size_t clients = 0;          ///< WebSocket clients connected now
  std::uint64_t connections = 0;    ///< WebSocket clients accepted
  std::uint64_t published = 0;      ///< frames `publish`ed
  std::uint64_t sent = 0;           ///< frames sent (summed over clients)
  std::uint64_t skipped = 0;        ///< frames a busy client did not get (summed over clients)
  std::uint64_t refused = 0;        ///< requests answered 403 (no or wrong token) or 503 (full)
  std::uint64_t received = 0;       ///< client messages received
  std::uint64_t inbox_dropped = 0;  ///< client messages dropped from a full inbox
  std::uint64_t pages = 0;          ///< pages served
};

/// A running server; it listens from construction to destruction. Thread-safe: `publish`,
/// `poll`, `send_text_to_all` and `stats` may be called from any thread.
class LiveServer {
 public:
  /// Listens on @p options' interface and port and serves @p page at `/` (text/html).
  /// @throws Error for invalid options, an address that is not one, or a port that cannot be
  ///         bound (naming it and why)
  LiveServer(std::string page, const LiveServerOptions& options = {});
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  /// The port listened on (the one chosen when the options said 0).
  int port() const noexcept;
  /// The access token (32 hex digits), empty when none is required.
  const std::string& token() const noexcept;
  /// The page's address: http://HOST:PORT/ with `?token=…` when one is required.
  std::string url() const;

  /// Makes @p frame (binary) the newest state frame. Never waits for a client; after the first
  /// frames of a size it allocates nothing.
  void publish(std::string_view frame);
  /// Sends @p text once to every client connected now and, as its first message, to every
  /// client that connects later (the model description a page builds its view from).
  void set_greeting(std::string text);
  /// Takes the oldest client message into @p message; false when there is none.
  bool poll(std::string& message);
  LiveServerStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when @p host names a loopback address (127.0.0.0/8, ::1, "localhost").
bool is_loopback_host(std::string_view host) noexcept;

}  // namespace mjarm
