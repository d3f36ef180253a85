#include "review/bounded_server.h"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <system_error>
#include <thread>

namespace surrogate::review {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// How long a closing connection is read from, and how much, before it is closed: a request
// refused before its body was read (403, 413) leaves that body unread, and closing over unread
// bytes makes the system reset the connection, which can drop the refusal before the client
// has read it.
constexpr milliseconds kLingerTime{1000};
constexpr std::size_t kLingerBytes = 16 << 20;
// The queue of connections waiting to be accepted (httplib listens with 5): a burst of
// connections from another program fills a short one faster than they are accepted, and the
// system then drops the page's own connection attempt, which the browser retries only a second
// later.
constexpr int kListenQueue = 1024;

int millisecondsOf(time_t seconds, time_t microseconds) {
  return static_cast<int>(seconds * 1000 + microseconds / 1000);
}

bool ready(int socket, short events, int timeoutMs) {
  if (timeoutMs <= 0) return false;
  pollfd p{socket, events, 0};
  return ::poll(&p, 1, timeoutMs) > 0;
}

// Each connection on a thread of its own, so that none waits for a slow or idle one; shutdown()
// (when the server stops) waits until every one has ended.
class ThreadPerConnection : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      ++running_;
    }
    auto task = [this, fn] {
      fn();
      const std::lock_guard<std::mutex> lock(mutex_);
      if (--running_ == 0) ended_.notify_all();
    };
    try {
      std::thread(task).detach();
    } catch (const std::system_error&) {
      task();  // no thread to be had: served on the accepting one rather than dropped
    }
  }
  void shutdown() override {
    std::unique_lock<std::mutex> lock(mutex_);
    ended_.wait(lock, [this] { return running_ == 0; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable ended_;
  std::size_t running_ = 0;
};

}  // namespace

// httplib's view of one connection: reads through a buffer, within the connection's deadline
// and byte budget until it is admitted, within the body's budget after.
class BoundedServer::Stream : public httplib::Stream {
 public:
  Stream(Connection& c, const Limits& limits, int readTimeoutMs, int writeTimeoutMs)
      : c_(c), limits_(limits), readTimeoutMs_(readTimeoutMs), writeTimeoutMs_(writeTimeoutMs) {}

  bool is_readable() const override { return start_ < end_ || ready(c_.socket, POLLIN, readWait()); }
  bool is_writable() const override { return ready(c_.socket, POLLOUT, writeTimeoutMs_); }

  ssize_t read(char* ptr, size_t size) override {
    if (start_ == end_) {
      const std::size_t budget = limits_.maxHeadBytes + (c_.admitted ? limits_.maxBodyBytes : 0);
      if (received_ >= budget || !ready(c_.socket, POLLIN, readWait())) return -1;
      const ssize_t n = ::recv(c_.socket, buffer_, std::min(sizeof buffer_, budget - received_), 0);
      if (n <= 0) return n;
      received_ += static_cast<std::size_t>(n);
      start_ = 0;
      end_ = static_cast<std::size_t>(n);
    }
    const std::size_t n = std::min(size, end_ - start_);
    std::memcpy(ptr, buffer_ + start_, n);
    start_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    return ::send(c_.socket, ptr, size, MSG_NOSIGNAL);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(true, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(false, ip, port); }
  socket_t socket() const override { return c_.socket; }

 private:
  // The longest wait for the next bytes: httplib's read timeout, and before admission no later
  // than the deadline, however steadily a slow client sends.
  int readWait() const {
    if (c_.admitted) return readTimeoutMs_;
    const auto left = std::chrono::duration_cast<milliseconds>(c_.opened + limits_.admitDeadline - Clock::now());
    return static_cast<int>(std::min<long long>(readTimeoutMs_, left.count()));
  }
  void address(bool peer, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t length = sizeof a;
    auto* at = reinterpret_cast<sockaddr*>(&a);
    if ((peer ? ::getpeername(c_.socket, at, &length) : ::getsockname(c_.socket, at, &length)) != 0) return;
    char host[NI_MAXHOST], service[NI_MAXSERV];
    if (::getnameinfo(at, length, host, sizeof host, service, sizeof service, NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
      ip = host;
      port = std::atoi(service);
    }
  }

  Connection& c_;
  const Limits& limits_;
  const int readTimeoutMs_, writeTimeoutMs_;
  char buffer_[4096];
  std::size_t start_ = 0, end_ = 0, received_ = 0;
};

thread_local BoundedServer::Connection* BoundedServer::current_ = nullptr;
thread_local BoundedServer* BoundedServer::currentServer_ = nullptr;

BoundedServer::BoundedServer(Limits limits) : limits_(limits) {
  new_task_queue = [] { return new ThreadPerConnection; };
  // SO_REUSEADDR alone (a port left in TIME_WAIT by the previous review is taken again at
  // once); not httplib's SO_REUSEPORT too, with which a second review on the same port would
  // start and the system would share the requests between the two.
  set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
}

BoundedServer::~BoundedServer() = default;

void BoundedServer::admitCurrentConnection() {
  if (!current_ || !currentServer_) return;
  const std::lock_guard<std::mutex> lock(currentServer_->connectionsMutex_);
  current_->admitted = true;
}

void BoundedServer::closeWaitingConnections() {
  const std::lock_guard<std::mutex> lock(connectionsMutex_);
  for (Connection* c : connections_)
    if (!c->admitted) ::shutdown(c->socket, SHUT_RDWR);
}

void BoundedServer::widenListenQueue() {
  if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, kListenQueue);
}

bool BoundedServer::enter(Connection& c) {
  const std::lock_guard<std::mutex> lock(connectionsMutex_);
  if (connections_.size() >= limits_.maxConnections) {
    const auto oldest = std::find_if(connections_.begin(), connections_.end(), [](Connection* o) { return !o->admitted; });
    if (oldest == connections_.end()) return false;
    // Its thread sees the end of its connection at once and ends; it is no longer listed, so
    // its socket (closed by that thread after leave()) is never touched from here again.
    ::shutdown((*oldest)->socket, SHUT_RDWR);
    connections_.erase(oldest);
  }
  connections_.push_back(&c);
  return true;
}

void BoundedServer::leave(Connection& c) {
  const std::lock_guard<std::mutex> lock(connectionsMutex_);
  connections_.remove(&c);
}

bool BoundedServer::process_and_close_socket(socket_t sock) {
  Connection c{sock, Clock::now()};
  bool served = false;
  if (enter(c)) {
    Stream stream(c, limits_, millisecondsOf(read_timeout_sec_, read_timeout_usec_),
                  millisecondsOf(write_timeout_sec_, write_timeout_usec_));
    current_ = &c;
    currentServer_ = this;
    bool closed = false;
    try {
      served = process_request(stream, /*close_connection=*/true, closed, nullptr);
    } catch (...) {
      served = false;  // the connection ends; the server goes on
    }
    current_ = nullptr;
    {
      // Listed, but no longer admitted, while it lingers: a new connection may close it.
      const std::lock_guard<std::mutex> lock(connectionsMutex_);
      c.admitted = false;
    }
    ::shutdown(sock, SHUT_WR);
    char scratch[16384];
    std::size_t drained = 0;
    const auto until = Clock::now() + kLingerTime;
    while (drained < kLingerBytes) {
      const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now()).count();
      if (!ready(sock, POLLIN, static_cast<int>(left))) break;
      const ssize_t n = ::recv(sock, scratch, sizeof scratch, 0);
      if (n <= 0) break;
      drained += static_cast<std::size_t>(n);
    }
    leave(c);
  }
  ::close(sock);
  return served;
}

}  // namespace surrogate::review
