// The review server's connections, each held within bounds (private to src/review: it is
// cpp-httplib's Server, Debian's libcpp-httplib 0.11, with the reading of each connection taken
// over). Left to itself that httplib reads a request line or a header of any length into memory,
// serves every connection from a pool of a few threads that a handful of slow or idle
// connections fill (every other request then waits), and keeps a connection open for more
// requests. Here:
//
//   - one request per connection, each in a thread of its own: no connection waits for another;
//   - a connection not yet admitted (its request not yet checked, review.h's key among the
//     checks) has `Limits::admitDeadline` from its opening to send its request line and headers,
//     however slowly it sends them (slowloris), and may send at most `maxHeadBytes` before it is
//     admitted; an admitted one then at most `maxBodyBytes` more;
//   - at most `maxConnections` open at once: a new one beyond closes the oldest connection not
//     yet admitted (an idle or slow one: the page's own requests are admitted within
//     milliseconds), so connections left open by another program never keep the page out.
//
//   BoundedServer server(BoundedServer::Limits{});
//   server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
//     if (!keyOf(req)) { res.status = 403; return httplib::Server::HandlerResponse::Handled; }
//     BoundedServer::admitCurrentConnection();
//     return httplib::Server::HandlerResponse::Unhandled;
//   });
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <list>
#include <mutex>

#include <httplib.h>

namespace surrogate::review {

class BoundedServer : public httplib::Server {
 public:
  struct Limits {
    // Open at once; a page needs a handful (a browser opens up to 6 to one server).
    std::size_t maxConnections = 128;
    // From a connection's opening to its request's last header: a browser sends them at once.
    std::chrono::milliseconds admitDeadline{5000};
    // The request line and headers: a browser's are under 2 KiB.
    std::size_t maxHeadBytes = 64 * 1024;
    // What an admitted request may send after its headers (its body).
    std::size_t maxBodyBytes = 1 << 20;
  };

  explicit BoundedServer(Limits limits);
  ~BoundedServer() override;

  // From the pre-routing handler (on the connection's own thread): the request on this
  // connection passed the server's checks, so it may send its body and is no longer closed to
  // make room for a new connection.
  static void admitCurrentConnection();
  // Ends every connection still reading (for stop(): none of them keeps the server's end
  // waiting for its deadline).
  void closeWaitingConnections();
  // The listening socket's queue of connections not yet accepted, raised from httplib's 5 so
  // that a burst of connections does not make the page's own wait for a retry; after bind.
  void widenListenQueue();

 private:
  struct Connection {
    int socket;
    std::chrono::steady_clock::time_point opened;
    std::atomic<bool> admitted{false};  // set under connectionsMutex_, read by its Stream without
  };
  class Stream;

  // httplib's accept loop calls this for each connection, on a thread of new_task_queue's.
  bool process_and_close_socket(socket_t sock) override;
  // Registers `c`, closing the oldest connection not yet admitted when there are maxConnections
  // already; false when all of them are admitted (c is then refused).
  bool enter(Connection& c);
  void leave(Connection& c);

  // The connection this thread serves, for admitCurrentConnection.
  static thread_local Connection* current_;
  static thread_local BoundedServer* currentServer_;

  Limits limits_;
  std::mutex connectionsMutex_;
  std::list<Connection*> connections_;  // oldest first
};

}  // namespace surrogate::review
