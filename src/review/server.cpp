// The review server (review.h) on cpp-httplib, Debian's libcpp-httplib (whose types stay in
// this file and bounded_server.h, private to src/review).
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "capture/lock.h"
#include "core/error.h"
#include "review/access_key.h"
#include "review/bounded_server.h"
#include "review/decisions.h"
#include "review/page.h"
#include "review/refusal_words.h"
#include "review/review.h"
#include "review/state.h"

namespace surrogate::review {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The longer side of a frame's preview: enough to place a highlight within a pixel or two on a
// screen, a fraction of a full-size frame's bytes.
constexpr int kPreviewSide = 1600;
// The largest request body: the decisions on a capture are a few kilobytes.
constexpr std::size_t kMaxBody = 1 << 20;

const char* const kJson = "application/json";

bool loopbackAddress(const std::string& address) {
  return address.rfind("127.", 0) == 0 || address == "::1" || address.rfind("::ffff:127.", 0) == 0;
}

void answer(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), kJson);
}

void answerError(httplib::Response& res, int status, const std::string& kind, const std::string& message) {
  answer(res, status, {{"error", kind}, {"message", message}});
}

// The sentence for an error httplib answered by itself (no handler ran, or none matched).
std::string statusSentence(int status) {
  switch (status) {
    case 400: return "the request is not one this server understands (malformed HTTP, or its body ended early)";
    case 404: return "no such page on this server";
    case 413: return "the request's body is larger than the 1 MiB this server takes";
    case 414: return "the request's address is too long";
    default: return "the request could not be answered (HTTP " + std::to_string(status) + ")";
  }
}

// The body's length as the request declares it, when it is a plain number.
std::optional<std::uint64_t> declaredLength(const std::string& header) {
  if (header.empty() || header.size() > 19) return std::nullopt;
  for (const char c : header)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  return std::stoull(header);
}

}  // namespace

struct ReviewServer::Impl {
  ReviewOptions options;
  fs::path capture;
  BoundedServer server{[] {
    BoundedServer::Limits limits;
    limits.maxBodyBytes = kMaxBody;
    return limits;
  }()};
  int port = 0;
  const AccessKey key = AccessKey::generate();

  // The state of the revision last read.
  std::mutex stateMutex;
  std::optional<CaptureState> state;
  // The frames' previews, by file and decode settings: a run that changes no setting leaves
  // them as they are (the originals are never written), so a new revision keeps them.
  std::map<std::string, std::string> previews;
  std::mutex previewMutex;  // one decode at a time: a raw frame is hundreds of megabytes

  // One Apply at a time, and where its run is.
  std::mutex applyMutex;
  std::mutex progressMutex;
  bool running = false;
  std::string progressLabel;
  double progressFraction = 0;

  CaptureState currentState() {
    const std::lock_guard<std::mutex> lock(stateMutex);
    if (!state || state->revision != captureRevision(capture))
      state = readCaptureState(capture, options.who, options.threads);
    return *state;
  }

  bool allowed(const httplib::Request& req, httplib::Response& res) {
    const std::string own = "127.0.0.1:" + std::to_string(port), ownName = "localhost:" + std::to_string(port);
    if (!loopbackAddress(req.remote_addr)) {
      answerError(res, 403, "forbidden", "this page answers only this computer (loopback interface)");
      return false;
    }
    // A page of another site that a DNS name of its own points at 127.0.0.1 still names that
    // name as the Host: refused (DNS rebinding).
    const std::string host = req.get_header_value("Host");
    if (host != own && host != ownName) {
      answerError(res, 403, "forbidden", "the request names another host than this server (" + own + ")");
      return false;
    }
    if (req.has_header("Origin")) {
      const std::string origin = req.get_header_value("Origin");
      if (origin != "http://" + own && origin != "http://" + ownName) {
        answerError(res, 403, "forbidden", "the request comes from another page than this server's");
        return false;
      }
    }
    // Another site's page may not make the browser ask anything of this server; but the
    // printed address, key included, comes to the browser from elsewhere by design (review's
    // launcher file, a link in a terminal), and whoever has the key is the operator.
    if (req.get_header_value("Sec-Fetch-Site") == "cross-site" && !firstLoad(req)) {
      answerError(res, 403, "forbidden", "the request comes from another site");
      return false;
    }
    if (!keyGiven(req, res)) return false;
    if (!bodyBounded(req, res)) return false;
    if (req.method == "POST" && req.get_header_value("Content-Type").rfind(kJson, 0) != 0) {
      answerError(res, 415, "unsupported", "send the decisions as application/json");
      return false;
    }
    // Checked: its body may be read, and its connection is no longer one to close for room.
    BoundedServer::admitCurrentConnection();
    return true;
  }

  // The page loaded from the address review printed, with the key.
  bool firstLoad(const httplib::Request& req) const {
    return req.method == "GET" && req.path == "/" && key.matches(req.get_param_value("key"));
  }

  // The key (access_key.h), from the cookie; or, on the page's first load, from the address
  // review printed, answered with the cookie (the page's script then takes the key out of the
  // address bar, kForgetKeyJs). Not a redirect to the address without the key: a browser
  // opened on review's launcher file (cli/command_review.cpp) would count that redirect as
  // coming from another site, and withhold the SameSite=Strict cookie from it.
  bool keyGiven(const httplib::Request& req, httplib::Response& res) {
    const std::string cookie = AccessKey::cookieName(port);
    bool fromCookie = false;
    for (std::size_t n = 0; n < req.get_header_value_count("Cookie"); ++n)
      fromCookie = key.matchesOneOf(cookieValues(req.get_header_value("Cookie", n), cookie)) || fromCookie;
    if (firstLoad(req)) {
      res.set_header("Set-Cookie", cookie + "=" + key.text() + "; Path=/; HttpOnly; SameSite=Strict");
      return true;
    }
    if (fromCookie) return true;
    const std::string message = "this review page opens only from the address `surrogate review` printed when it "
                                "started (http://127.0.0.1:" + std::to_string(port) +
                                "/?key=...): open that address in a browser on this computer";
    if (req.path.rfind("/api/", 0) == 0) {
      answerError(res, 403, "forbidden", message);
    } else {
      res.status = 403;
      res.set_content(message + "\n", "text/plain; charset=utf-8");
    }
    return false;
  }

  // A body the server reads is at most kMaxBody bytes as it arrives and as it is used: its
  // length is declared and within the bound (413 beyond), and it comes neither in chunks (of no
  // declared length) nor compressed (httplib would inflate it without bound). The page's fetch
  // sends neither.
  bool bodyBounded(const httplib::Request& req, httplib::Response& res) {
    if (req.has_header("Transfer-Encoding")) {
      answerError(res, 411, "length required", "send the body whole, with its length (Content-Length), not in chunks");
      return false;
    }
    const std::string encoding = req.get_header_value("Content-Encoding");
    if (!encoding.empty() && encoding != "identity") {
      answerError(res, 415, "unsupported", "send the body uncompressed (no Content-Encoding " + encoding + ")");
      return false;
    }
    if (!req.has_header("Content-Length")) {
      if (req.method == "GET" || req.method == "HEAD") return true;
      answerError(res, 411, "length required", "send the body with its length (Content-Length)");
      return false;
    }
    const std::optional<std::uint64_t> length = declaredLength(req.get_header_value("Content-Length"));
    if (!length) {
      answerError(res, 400, "bad request", "the request's Content-Length is not a number of bytes");
      return false;
    }
    if (*length > kMaxBody) {
      answerError(res, 413, "too large",
                  "the request's body is " + std::to_string(*length) + " bytes, more than the " +
                      std::to_string(kMaxBody) + " (1 MiB) this server takes; the decisions on a capture are a few kilobytes");
      return false;
    }
    return true;
  }

  void apply(const httplib::Request& req, httplib::Response& res) {
    std::unique_lock<std::mutex> one(applyMutex, std::try_to_lock);
    if (!one.owns_lock()) {
      answerError(res, 423, "busy", "a run is going on this capture from this page; wait until it ends, then apply again");
      return;
    }
    std::vector<std::string> arguments;
    std::string revision;
    try {
      revision = revisionOf(req.body);
      arguments = argumentsFor(req.body);
    } catch (const Error& e) {
      answerError(res, 400, "usage", e.text());
      return;
    }
    const std::string now = captureRevision(capture);
    if (revision != now) {
      json body = {{"error", "stale"},
                   {"message", "the capture's record changed since this page was loaded (another command or page "
                               "ran); nothing was applied. The page now shows the new record: look at it, then "
                               "apply again"},
                   {"revision", now}};
      answer(res, 409, body);
      return;
    }
    std::vector<std::string> given = options.leadingOptions;
    given.insert(given.end(), arguments.begin(), arguments.end());
    {
      const std::lock_guard<std::mutex> lock(progressMutex);
      running = true;
      progressLabel = "Starting";
      progressFraction = 0;
    }
    int status = 200;
    json body;
    std::string terminalText;
    try {
      options.runner(given, revision, [this](const std::string& label, double fraction) {
        const std::lock_guard<std::mutex> lock(progressMutex);
        progressLabel = label;
        progressFraction = fraction;
      });
      body = {{"outcome", "applied"}};
    } catch (const Error& e) {
      // The run's own words: a refused option names it and says what to do; a failed run is in
      // the carrier's history (the page shows it once reloaded); the capture held by another
      // command is its lock's message.
      status = e.step() == capture::kCaptureHeldStep ? 423 : e.step() == kStaleStep ? 409 : e.kind() == ErrorKind::Usage ? 400 : 422;
      // A refusal the page words itself says what to do on the page (refusal_words.h); the
      // terminal, which prints the command line, keeps the run's words.
      body = {{"error", status == 423 ? "busy" : status == 409 ? "stale" : status == 400 ? "usage" : "failed"},
              {"message", status == 409 ? e.message() : pageWords(e)}};
      terminalText = e.text();
    } catch (const std::exception& e) {
      status = 500;
      body = {{"error", "internal"}, {"message", e.what()}};
    }
    {
      const std::lock_guard<std::mutex> lock(progressMutex);
      running = false;
    }
    body["options"] = given;
    body["revision"] = captureRevision(capture);
    if (options.applied)
      options.applied(given, status == 200 ? "applied" : terminalText.empty() ? body.value("message", "") : terminalText);
    answer(res, status, body);
  }
};

ReviewServer::ReviewServer(ReviewOptions options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = std::move(options);
  if (m.options.port < 0 || m.options.port > 65535)
    throw Error(ErrorKind::Usage, "--port " + std::to_string(m.options.port), "command line",
                "needs a port number from 1 to 65535, or 0 for a free one");
  m.capture = fs::absolute(m.options.capture).lexically_normal();
  capture::requireCaptureFolder(m.capture);
  m.currentState();  // a carrier that cannot be read is said now, not in the browser

  BoundedServer& s = m.server;
  s.set_payload_max_length(kMaxBody);
  s.set_default_headers({{"Cache-Control", "no-store"},
                         {"X-Content-Type-Options", "nosniff"},
                         {"X-Frame-Options", "DENY"},
                         {"Referrer-Policy", "no-referrer"},
                         {"Cross-Origin-Resource-Policy", "same-origin"}});
  s.set_pre_routing_handler([&m](const httplib::Request& req, httplib::Response& res) {
    return m.allowed(req, res) ? httplib::Server::HandlerResponse::Unhandled
                               : httplib::Server::HandlerResponse::Handled;
  });
  s.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_header("Content-Security-Policy", kPageSecurityPolicy);
    res.set_content(pageHtml(), "text/html; charset=utf-8");
  });
  s.Get("/review.js", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(pageScript(), "text/javascript; charset=utf-8");
  });
  s.Get("/review.css", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(pageCss(), "text/css; charset=utf-8");
  });
  s.Get("/api/state", [&m](const httplib::Request&, httplib::Response& res) {
    try {
      res.set_content(m.currentState().json, kJson);
    } catch (const Error& e) {
      answerError(res, 500, "unreadable", e.text());
    }
  });
  // The carrier's revision alone, which the page asks every few seconds: a record that another
  // command changed meanwhile is shown without waiting for an Apply to be refused.
  s.Get("/api/revision", [&m](const httplib::Request&, httplib::Response& res) {
    answer(res, 200, {{"revision", captureRevision(m.capture)}});
  });
  s.Get("/api/progress", [&m](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(m.progressMutex);
    answer(res, 200, {{"running", m.running}, {"label", m.progressLabel}, {"fraction", m.progressFraction}});
  });
  s.Get(R"(/frame/(\d{1,6})\.jpg)", [&m](const httplib::Request& req, httplib::Response& res) {
    const std::size_t n = std::stoul(req.matches[1].str());
    CaptureState st;
    try {
      st = m.currentState();
    } catch (const Error& e) {
      answerError(res, 500, "unreadable", e.text());
      return;
    }
    if (n >= st.frames.size()) {
      answerError(res, 404, "not found", "the capture has no frame " + std::to_string(n));
      return;
    }
    std::string key = st.frames[n].path;
    for (const auto& [name, value] : st.decodeSettings) key += "\n" + name + "=" + value;
    const std::lock_guard<std::mutex> decode(m.previewMutex);
    std::string& jpeg = m.previews[key];
    if (jpeg.empty()) {
      try {
        jpeg = framePreview(m.capture, st.frames[n], st.decodeSettings, kPreviewSide,
                            std::max(st.frameWidth, st.frameHeight));
      } catch (const Error& e) {
        m.previews.erase(key);
        answerError(res, 422, "unreadable", e.text());
        return;
      }
    }
    res.set_content(jpeg, "image/jpeg");
  });
  // The options an Apply would run with, the command line's own first (--operator): the page
  // shows exactly the command the run records.
  s.Post("/api/options", [&m](const httplib::Request& req, httplib::Response& res) {
    try {
      std::vector<std::string> given = m.options.leadingOptions;
      for (std::string& a : argumentsFor(req.body)) given.push_back(std::move(a));
      answer(res, 200, {{"options", given}});
    } catch (const Error& e) {
      answerError(res, 400, "usage", e.text());
    }
  });
  s.Post("/api/apply", [&m](const httplib::Request& req, httplib::Response& res) { m.apply(req, res); });
  s.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) answerError(res, res.status, "error", statusSentence(res.status));
  });

  // The loopback interface only: nothing on the network can reach the page.
  if (m.options.port == 0) {
    m.port = s.bind_to_any_port("127.0.0.1");
    if (m.port <= 0)
      throw Error(ErrorKind::Input, "127.0.0.1", "review", "no free port to serve the review page on");
  } else {
    if (!s.bind_to_port("127.0.0.1", m.options.port))
      throw Error(ErrorKind::Input, "127.0.0.1:" + std::to_string(m.options.port), "review",
                  "cannot serve the review page on this port (another program uses it, or it is not allowed); "
                  "choose another with --port, or --port 0 for a free one");
    m.port = m.options.port;
  }
  s.widenListenQueue();
}

ReviewServer::~ReviewServer() { stop(); }

int ReviewServer::port() const { return impl_->port; }

std::string ReviewServer::address() const {
  return "http://127.0.0.1:" + std::to_string(impl_->port) + "/?key=" + impl_->key.text();
}

void ReviewServer::serve() { impl_->server.listen_after_bind(); }

void ReviewServer::stop() {
  if (!impl_) return;
  impl_->server.stop();
  impl_->server.closeWaitingConnections();
}

}  // namespace surrogate::review
