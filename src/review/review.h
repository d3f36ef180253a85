// `surrogate review`: the capture's decisions taken in a browser page instead of typed options.
//
// A small HTTP server on the loopback interface serves one page (review/page.h) that shows
// every frame of the capture with its sphere and highlight overlays, the light hemisphere
// coloured by the fit's residual, the plausibility checks, the standing decisions and the
// description. The user drags a sphere's circle, clicks a highlight, leaves a frame out with a
// reason, accepts or withdraws a check, types the title, creator, rights and licence; "Apply"
// sends them back, and the server turns them into the options of `surrogate run`
// (review/decisions.h argumentsFor) and hands those to the runner the command line gives it:
// the same parse of the options and the same run as `surrogate run`, so that a decision taken in
// the page and the same decision typed as an option make the same carrier. Nothing is written
// but through that run (the capture's lock, the all-or-nothing commit of run/run_commit.h).
//
// The server answers only requests that come from the loopback interface, name it as their Host
// (127.0.0.1:PORT or localhost:PORT, against DNS rebinding), when they carry an Origin, come
// from the page itself, and carry the key made when it started (access_key.h: printed in the
// address, then a cookie), which no other account of the computer has; anything else is 403.
// A request body is at most 1 MiB, sent whole and uncompressed (413, 411, 415), and each
// connection is held within a deadline and a byte budget (bounded_server.h), so that slow or
// idle connections of another program never keep the page waiting. Every state it gives carries the carrier's
// revision (its SHA-256); an Apply whose revision is no longer the carrier's is refused with 409
// ("the capture changed since the page was loaded"), so a stale page never overrides a newer
// record. One Apply at a time: a second one while a run goes is refused with 423.
//
//   ReviewOptions o;
//   o.capture = "/data/stela12";
//   o.runner = [](const std::vector<std::string>& options, const std::string& revision,
//                 const ProgressFunction& progress) {...};
//   ReviewServer server(o);
//   std::cout << server.address() << "\n";  // http://127.0.0.1:PORT/?key=KEY
//   server.serve();  // until stop()
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace surrogate::review {

// (label, fraction done 0..1) of the run an Apply started.
using ProgressFunction = std::function<void(const std::string& label, double fraction)>;

// Runs `surrogate run CAPTURE OPTIONS...` in this process (the command line's parse of the
// options and run::runCapture, with the capture's lock held for the whole run), reporting its
// progress. Once it holds the lock, and before it runs, it calls requireRevision(capture,
// revision): the page's revision was checked before, but another command may have committed
// between that check and the lock. Throws surrogate::Error as `surrogate run` does: Usage for a
// decision the options refuse (nothing written), Input for a run that failed (recorded in the
// carrier's history); and requireRevision's.
using Runner = std::function<void(const std::vector<std::string>& options, const std::string& revision,
                                  const ProgressFunction& progress)>;

// The step name of the Error requireRevision throws, which the server answers with 409.
inline constexpr const char* kStaleStep = "stale page";
// Throws Error(Usage, capture, kStaleStep, ...) unless the capture's carrier is at `revision`
// (the "sha256:HEX" of its file, or "none"), the one the page was shown.
void requireRevision(const std::filesystem::path& capture, const std::string& revision);

struct ReviewOptions {
  std::filesystem::path capture;
  int port = 0;  // 0: a free port the system chooses
  int threads = 0;  // for the frames' previews; 0 = all cores
  // Options put first in every Apply's option list (e.g. "--operator", "Ana"): how the command
  // line gave who runs this, so that the run records it as `surrogate run` would.
  std::vector<std::string> leadingOptions;
  std::string who;  // shown in the page: who the decisions will be recorded as made by
  Runner runner;
  // Called after each Apply with the equivalent command line's options and its outcome
  // ("applied", or the error's text), for the terminal. May be empty.
  std::function<void(const std::vector<std::string>& options, const std::string& outcome)> applied;
};

class ReviewServer {
 public:
  // Binds 127.0.0.1:options.port. Throws Error(Input) when the capture is not a capture folder
  // or the port cannot be bound (in use, or not allowed), Error(Usage) for a port outside
  // 0..65535.
  explicit ReviewServer(ReviewOptions options);
  ~ReviewServer();
  ReviewServer(const ReviewServer&) = delete;
  ReviewServer& operator=(const ReviewServer&) = delete;

  int port() const;
  // The page's address with its key, http://127.0.0.1:PORT/?key=KEY: the one to print and open.
  std::string address() const;
  // Answers requests until stop() (from another thread or a signal handler's thread).
  void serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace surrogate::review
