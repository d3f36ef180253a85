// Who and what surrogate review's server admits (review.h, access_key.h, bounded_server.h), as
// another account of the computer would try it: without the key printed in the address; with
// bodies too large, in chunks or compressed; with slow or idle connections held open; on the
// port of a review already running; the key among the browser's arguments; and an Apply over a
// commit a killed command left half-done.
#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "e2e_support.h"
#include "review_process.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A TCP connection to the review's port, opened and left as the test says (no HTTP client).
class RawConnection {
 public:
  explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }
  bool send(const std::string& bytes) { return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size()); }
  // Whether the server has ended the connection (end of stream or reset), waiting up to `wait`.
  bool endedBy(std::chrono::milliseconds wait) {
    timeval tv{static_cast<time_t>(wait.count() / 1000), static_cast<suseconds_t>(wait.count() % 1000 * 1000)};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n == 0) return true;
      if (n < 0) return errno != EAGAIN && errno != EWOULDBLOCK;
    }
  }

 private:
  int fd_;
  bool connected_ = false;
};

json bodyOf(const httplib::Result& res) { return json::parse(res->body); }

// The status of the page's own request, as it asks every few seconds; -1 when no answer came
// within 4 s (the server of 9cd773a, behind slow or idle connections).
int pageRequest(const review_test::ReviewProcess& review) {
  httplib::Client client = review_test::pageClient(review);
  client.set_connection_timeout(4);
  client.set_read_timeout(4);
  const auto res = client.Get("/api/revision");
  return res ? res->status : -1;
}

}  // namespace

TEST_CASE("review: without the key printed in the address, nothing is served and nothing applied", "[review]") {
  const fs::path dir = e2e::freshDir("review-key");
  const fs::path capture = e2e::processedCapture(dir);
  review_test::ReviewProcess review(capture, {}, dir / "review.log");
  const std::string port = std::to_string(review.port());
  REQUIRE(review.key().size() == 64);
  const json state = bodyOf(review_test::pageClient(review).Get("/api/state"));

  // Another account knows the port (ss -ltn shows it) but not the key.
  httplib::Client stranger("127.0.0.1", review.port());
  for (const char* path : {"/", "/review.js", "/review.css", "/api/state", "/api/revision", "/api/progress", "/frame/2.jpg"}) {
    const auto res = stranger.Get(path);
    REQUIRE(res);
    INFO(path);
    CHECK(res->status == 403);
    CHECK(res->body.find("open that address") != std::string::npos);
    CHECK(res->body.find(review.key()) == std::string::npos);
  }
  const std::string bytes = e2e::bytesOf(capture / "assembly-files/carrier.xml");
  const json hijack = {{"revision", state["revision"]}, {"title", "Hijacked"}};
  const auto posted = stranger.Post("/api/apply", {{"Origin", "http://127.0.0.1:" + port}}, hijack.dump(), "application/json");
  REQUIRE(posted);
  CHECK(posted->status == 403);
  CHECK(e2e::bytesOf(capture / "assembly-files/carrier.xml") == bytes);

  // A wrong key of the right length, the key under another port's cookie, the key in the
  // address of anything but the page: refused.
  std::string wrong = review.key();
  wrong[10] = wrong[10] == 'a' ? 'b' : 'a';
  CHECK(stranger.Get("/api/state", {{"Cookie", "surrogate-review-" + port + "=" + wrong}})->status == 403);
  CHECK(stranger.Get("/api/state", {{"Cookie", "surrogate-review-1=" + review.key()}})->status == 403);
  CHECK(stranger.Get("/api/state?key=" + review.key())->status == 403);

  // The printed address: the page, and the key as a cookie the page's script cannot read and no
  // other site's page makes the browser send (the page then takes the key out of the address
  // bar: tests/review/browser).
  const auto first = stranger.Get("/?key=" + review.key());
  REQUIRE(first);
  CHECK(first->status == 200);
  CHECK(first->body.find("<script src=\"/review.js\">") != std::string::npos);
  const std::string cookie = first->get_header_value("Set-Cookie");
  CHECK(cookie.find("surrogate-review-" + port + "=" + review.key() + ";") == 0);
  CHECK(cookie.find("HttpOnly") != std::string::npos);
  CHECK(cookie.find("SameSite=Strict") != std::string::npos);
  // Opened from review's launcher file or a link elsewhere, the address is a navigation from
  // another site: let in with the key, refused without it.
  CHECK(stranger.Get("/?key=" + review.key(), {{"Sec-Fetch-Site", "cross-site"}})->status == 200);
  CHECK(stranger.Get("/", {{"Sec-Fetch-Site", "cross-site"}})->status == 403);
  // A cookie of the same name set by another program's page on 127.0.0.1, sent first, does not
  // hide the page's own.
  const auto page = stranger.Get(
      "/", {{"Cookie", "surrogate-review-" + port + "=planted; other=1; surrogate-review-" + port + "=" + review.key()}});
  REQUIRE(page);
  CHECK(page->status == 200);
  CHECK(page->body.find("<script src=\"/review.js\">") != std::string::npos);
}

TEST_CASE("review: a body is at most 1 MiB however it is sent, and a larger one is told so", "[review]") {
  const fs::path dir = e2e::freshDir("review-body");
  const fs::path capture = e2e::processedCapture(dir);
  review_test::ReviewProcess review(capture, {}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);
  // Valid decisions padded past 1 MiB with spaces: read whole, they would be answered 200.
  const std::string padded = "{\"title\": \"Stela 12\"" + std::string(2 << 20, ' ') + "}";
  REQUIRE(client.Post("/api/options", "{\"title\": \"Stela 12\"}", "application/json")->status == 200);

  SECTION("with its length declared: 413, saying the body is too large") {
    const auto res = client.Post("/api/options", padded, "application/json");
    REQUIRE(res);
    CHECK(res->status == 413);
    CHECK(bodyOf(res)["message"].get<std::string>().find("1 MiB") != std::string::npos);
  }
  SECTION("in chunks, of no declared length: refused") {
    std::size_t sent = 0;
    const auto res = client.Post(
        "/api/options",
        [&](std::size_t, httplib::DataSink& sink) {
          const std::size_t n = std::min<std::size_t>(64 * 1024, padded.size() - sent);
          sink.write(padded.data() + sent, n);
          sent += n;
          if (sent == padded.size()) sink.done();
          return true;
        },
        "application/json");
    REQUIRE(res);
    CHECK(res->status == 411);
    CHECK(bodyOf(res)["message"].get<std::string>().find("not in chunks") != std::string::npos);
  }
  SECTION("compressed (2 MiB in a few kilobytes of gzip): refused, never inflated") {
    client.set_compress(true);
    const auto res = client.Post("/api/options", padded, "application/json");
    REQUIRE(res);
    CHECK(res->status == 415);
    CHECK(bodyOf(res)["message"].get<std::string>().find("uncompressed") != std::string::npos);
  }
  CHECK(review.stop() == 0);
}

TEST_CASE("review: slow and idle connections of another program never keep the page waiting", "[review]") {
  const fs::path dir = e2e::freshDir("review-connections");
  const fs::path capture = e2e::processedCapture(dir);
  review_test::ReviewProcess review(capture, {}, dir / "review.log");

  SECTION("slow ones (slowloris), more than httplib's pool of threads: the page answers, they are closed") {
    // More than the threads httplib would serve them with (8, or one fewer than the cores).
    const std::size_t count = std::max<std::size_t>(8, std::thread::hardware_concurrency()) + 2;
    std::vector<std::unique_ptr<RawConnection>> slow;
    for (std::size_t n = 0; n < count; ++n) {
      slow.push_back(std::make_unique<RawConnection>(review.port()));
      REQUIRE(slow.back()->connected());
      slow.back()->send("GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\n");
    }
    // A header byte every 200 ms each: never idle long enough for a read timeout.
    std::atomic<bool> dripping{true};
    std::thread drip([&] {
      while (dripping) {
        for (auto& c : slow) c->send("X");
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    CHECK(pageRequest(review) == 200);
    // Each had 5 s from its opening to finish its headers, however steadily it sent them.
    CHECK(slow.front()->endedBy(std::chrono::milliseconds(7000)));
    dripping = false;
    drip.join();
  }
  SECTION("idle ones, more than the connections held at once: the page answers") {
    std::vector<std::unique_ptr<RawConnection>> idle;
    for (int n = 0; n < 300; ++n) {
      idle.push_back(std::make_unique<RawConnection>(review.port()));
      REQUIRE(idle.back()->connected());
    }
    CHECK(pageRequest(review) == 200);
    // The oldest were closed to make room for the newer ones.
    CHECK(idle.front()->endedBy(std::chrono::milliseconds(1000)));
  }
  CHECK(review.stop() == 0);
}

TEST_CASE("review: a port another review serves is refused, exit 1 naming it", "[review]") {
  const fs::path dir = e2e::freshDir("review-port");
  const fs::path capture = e2e::processedCapture(dir);
  review_test::ReviewProcess first(capture, {}, dir / "first.log");
  const std::string port = std::to_string(first.port());
  // Without SO_REUSEPORT the second cannot bind: it ends at once (timeout(1) would say 124).
  const e2e::CommandResult second = e2e::runShell("timeout 10 " + std::string(SURROGATE_EXE) + " review " +
                                                  e2e::quote(capture) + " --no-browser --port " + port + " 2>&1");
  INFO(second.output);
  CHECK(second.exitCode == 1);
  CHECK(second.output.find("127.0.0.1:" + port) != std::string::npos);
  CHECK(first.stop() == 0);
}

TEST_CASE("review: a commit a killed command left half-done is finished before the page's revision is checked",
          "[review]") {
  const fs::path dir = e2e::freshDir("review-pending");
  const fs::path capture = e2e::processedCapture(dir);
  const fs::path carrierFile = capture / "assembly-files/carrier.xml";
  const std::string shown = "sha256:" + e2e::runShell("sha256sum " + e2e::quote(carrierFile)).output.substr(0, 64);
  // A run killed between moving its results and its carrier (run/run_commit.cpp's fault
  // injection): the old carrier is still in place, the journal says the commit must be finished.
  const e2e::CommandResult killed = e2e::runShell("SURROGATE_FAULT_INJECTION=commit " + std::string(SURROGATE_EXE) +
                                                  " run " + e2e::quote(capture) + " --title Killed --quiet 2>&1");
  REQUIRE(killed.exitCode == 137);
  REQUIRE(fs::exists(capture / ".surrogate/commit"));

  review_test::ReviewProcess review(capture, {}, dir / "review.log");
  httplib::Client client = review_test::pageClient(review);
  // The page showed the old carrier: its Apply is refused once the commit is finished.
  const json decisions = {{"revision", shown}, {"title", "From the page"}};
  const auto res = client.Post("/api/apply", {{"Origin", "http://127.0.0.1:" + std::to_string(review.port())}},
                               decisions.dump(), "application/json");
  REQUIRE(res);
  INFO(res->body);
  CHECK(res->status == 409);
  const std::string carrier = e2e::bytesOf(carrierFile);
  CHECK(carrier.find("Killed") != std::string::npos);
  CHECK(carrier.find("From the page") == std::string::npos);
  CHECK_FALSE(fs::exists(capture / ".surrogate/commit"));
  CHECK(bodyOf(res)["revision"] != shown);
  CHECK(review.stop() == 0);
}

TEST_CASE("review: the browser is started on a file only this account reads, never with the key as argument",
          "[review]") {
  const fs::path dir = e2e::freshDir("review-launcher");
  const fs::path capture = e2e::processedCapture(dir);
  // A desktop whose xdg-open records what it was given (every account can list a program's
  // arguments: ps, /proc/PID/cmdline).
  const fs::path bin = dir / "bin", given = dir / "xdg-open-arguments";
  fs::create_directories(bin);
  {
    std::ofstream script(bin / "xdg-open");
    script << "#!/bin/sh\nprintf '%s' \"$*\" > " << e2e::quote(given) << "\n";
  }
  fs::permissions(bin / "xdg-open", fs::perms::owner_all);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin:/bin";
  const char* display = std::getenv("DISPLAY");
  const std::string savedDisplay = display ? display : "";
  ::setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
  ::setenv("DISPLAY", ":99", 1);
  std::string key, argument;
  {
    // With the browser opened (no --no-browser): the process's own words, not ReviewProcess's.
    const pid_t pid = e2e::startSurrogate({"review", capture.string(), "--port", "0"}, dir / "review.log");
    ::setenv("PATH", path.c_str(), 1);
    if (display)
      ::setenv("DISPLAY", savedDisplay.c_str(), 1);
    else
      ::unsetenv("DISPLAY");
    // Both the browser's arguments and the address printed: the two may come in either order
    // (under load the browser was started before the address reached the log).
    std::string printed;
    for (int tries = 0; tries < 200; ++tries) {
      printed = e2e::bytesOf(dir / "review.log");
      if (fs::exists(given) && printed.find("?key=") != std::string::npos) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const auto at = printed.find("?key=");
    REQUIRE(at != std::string::npos);
    key = printed.substr(at + 5, 64);
    REQUIRE(fs::exists(given));
    argument = e2e::bytesOf(given);
    INFO(argument);
    CHECK(argument.find(key) == std::string::npos);
    // The file holds the address with the key, in a folder only its owner can open.
    const fs::path file = argument;
    REQUIRE(fs::exists(file));
    CHECK(e2e::bytesOf(file).find("http://127.0.0.1:") != std::string::npos);
    CHECK(e2e::bytesOf(file).find("?key=" + key) != std::string::npos);
    CHECK((fs::status(file.parent_path()).permissions() & (fs::perms::group_all | fs::perms::others_all)) == fs::perms::none);
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
  }
  CHECK_FALSE(fs::exists(fs::path(argument).parent_path()));  // removed when the review stopped
}
