#pragma once
/// @file
/// A blocking HTTP and WebSocket client for the live server's tests (Boost.Beast).

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <string>

namespace mjarm::test {

namespace web_net = boost::asio;
namespace web_beast = boost::beast;

/// The status and body of GET @p target on 127.0.0.1:@p port.
inline std::pair<int, std::string> http_get(int port, const std::string& target) {
  web_net::io_context io;
  web_beast::tcp_stream stream(io);
  stream.expires_after(std::chrono::seconds(30));
  stream.connect(web_net::ip::tcp::endpoint(web_net::ip::make_address("127.0.0.1"),
                                            static_cast<unsigned short>(port)));
  web_beast::http::request<web_beast::http::empty_body> request(web_beast::http::verb::get, target,
                                                                11);
  request.set(web_beast::http::field::host, "127.0.0.1");
  web_beast::http::write(stream, request);
  web_beast::flat_buffer buffer;
  web_beast::http::response<web_beast::http::string_body> response;
  web_beast::http::read(stream, buffer, response);
  return {static_cast<int>(response.result_int()), response.body()};
}

/// A WebSocket client of ws://127.0.0.1:PORT@p target; the handshake throws
/// boost::system::system_error when the server refuses it.
class WebSocketClient {
 public:
  WebSocketClient(int port, const std::string& target) : ws_(io_) {
    web_beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(30));
    web_beast::get_lowest_layer(ws_).connect(web_net::ip::tcp::endpoint(
        web_net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)));
    ws_.handshake("127.0.0.1", target);
    web_beast::get_lowest_layer(ws_).expires_never();
  }
  /// The next message (blocks); @p text tells whether it was text.
  std::string read(bool* text = nullptr) {
    web_beast::flat_buffer buffer;
    ws_.read(buffer);
    if (text != nullptr) *text = ws_.got_text();
    return web_beast::buffers_to_string(buffer.data());
  }
  void send(const std::string& message) {
    ws_.text(true);
    ws_.write(web_net::buffer(message));
  }
  /// Makes the socket's receive buffer small, so that a client that stops reading stalls the
  /// server's sends soon.
  void shrink_receive_buffer() {
    web_beast::get_lowest_layer(ws_).socket().set_option(
        web_net::socket_base::receive_buffer_size(4096));
  }

 private:
  web_net::io_context io_;
  web_beast::websocket::stream<web_beast::tcp_stream> ws_;
};

}  // namespace mjarm::test
