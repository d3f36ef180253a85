// The payload of a bag: checking the files given before anything is written, then reading each
// once, the same buffer feeding the output, SHA-256 and SHA-512. The two digests run on worker
// threads beside the write, so packing costs about one SHA-512 pass (bench/pack_bench measures
// it against sha512sum); this is where a pack spends its time, kept apart from what it writes.
#include "archive/bag_payload.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

#include "archive/bag_output.h"
#include "core/digest.h"
#include "core/error.h"

namespace surrogate::archive {

bool safeRelative(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.back() == '/') return false;
  if (path.find('\0') != std::string::npos) return false;
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t slash = path.find('/', start);
    if (slash == std::string::npos) slash = path.size();
    const std::string segment = path.substr(start, slash - start);
    if (segment.empty() || segment == "." || segment == "..") return false;
    start = slash + 1;
  }
  return true;
}

namespace {

// One digest computed on its own thread, chunk by chunk: SHA-256 and SHA-512 of the same
// buffer run side by side (and beside the write), so packing costs about one SHA-512 pass.
class DigestWorker {
 public:
  explicit DigestWorker(DigestAlgorithm algorithm) : digest_({algorithm}), thread_([this] { loop(); }) {}
  ~DigestWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  DigestWorker(const DigestWorker&) = delete;
  DigestWorker& operator=(const DigestWorker&) = delete;

  // Starts hashing `size` bytes at `data`; the buffer must stay untouched until wait().
  void submit(const void* data, std::size_t size) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      data_ = data;
      size_ = size;
      busy_ = true;
    }
    wake_.notify_all();
  }
  void wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return !busy_; });
  }
  // Finishes (after wait()) and returns the hex digest; starts a new one for the next file.
  std::string finish(DigestAlgorithm algorithm) {
    wait();
    std::string hex = digest_.hex(algorithm);
    digest_ = MultiDigest({algorithm});
    return hex;
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || busy_; });
      if (stop_) return;
      const void* data = data_;
      const std::size_t size = size_;
      lock.unlock();
      digest_.update(data, size);
      lock.lock();
      busy_ = false;
      done_.notify_all();
    }
  }

  MultiDigest digest_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const void* data_ = nullptr;
  std::size_t size_ = 0;
  bool busy_ = false, stop_ = false;
  std::thread thread_;
};

// Both digests of a stream: on two worker threads when the machine has two cores or more,
// else in this thread.
class PayloadHasher {
 public:
  PayloadHasher() {
    if (std::thread::hardware_concurrency() >= 2) {
      sha256_ = std::make_unique<DigestWorker>(DigestAlgorithm::Sha256);
      sha512_ = std::make_unique<DigestWorker>(DigestAlgorithm::Sha512);
    }
  }
  bool parallel() const { return sha256_ != nullptr; }
  // Parallel: starts hashing (the buffer must stay untouched until wait()). Else: hashes now.
  void submit(const void* data, std::size_t size) {
    if (parallel()) {
      sha256_->submit(data, size);
      sha512_->submit(data, size);
    } else {
      serial_.update(data, size);
    }
  }
  void wait() {
    if (parallel()) {
      sha256_->wait();
      sha512_->wait();
    }
  }
  std::pair<std::string, std::string> finish() {
    if (parallel()) return {sha256_->finish(DigestAlgorithm::Sha256), sha512_->finish(DigestAlgorithm::Sha512)};
    std::pair<std::string, std::string> out{serial_.hex(DigestAlgorithm::Sha256), serial_.hex(DigestAlgorithm::Sha512)};
    serial_ = MultiDigest({DigestAlgorithm::Sha256, DigestAlgorithm::Sha512});
    return out;
  }

 private:
  std::unique_ptr<DigestWorker> sha256_, sha512_;
  MultiDigest serial_{{DigestAlgorithm::Sha256, DigestAlgorithm::Sha512}};
};

// Streams one payload file into the sink, hashing the same buffer. Returns its digests.
// Two buffers alternate: while the digests of one run, the other is being read.
PayloadDigest streamFile(const PayloadFile& src, Sink& sink, PayloadHasher& hasher,
                         std::vector<unsigned char> (&buffers)[2],
                         const std::function<void(std::uint64_t)>& advance) {
  const std::string shown = src.in->source.string();
  const int fd = ::open(src.in->source.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) {
    throwInputError(shown, "packing",
                    std::string("cannot be read (") + std::strerror(errno) +
                        "); check its permissions, or copy it again from the card");
  }
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
  struct Closer {
    int fd;
    PayloadHasher& hasher;
    ~Closer() {
      hasher.wait();  // never leave a worker reading a buffer on the way out
      ::close(fd);
    }
  } closer{fd, hasher};
  sink.begin(src.in->bagPath, src.size);
  std::uint64_t done = 0;
  int current = 0;
  for (;;) {
    std::vector<unsigned char>& buffer = buffers[current];
    ssize_t n;
    do {
      n = ::read(fd, buffer.data(), buffer.size());
    } while (n < 0 && errno == EINTR);
    if (n < 0) {
      throwInputError(shown, "packing",
                      std::string("reading failed (") + std::strerror(errno) +
                          "); the disk or card may be failing: copy the file again");
    }
    if (n == 0) break;
    if (done + static_cast<std::uint64_t>(n) > src.size) {  // grew: reported below
      done += static_cast<std::uint64_t>(n);
      break;
    }
    hasher.wait();  // the previous chunk's digests are done: its buffer may be reused next
    hasher.submit(buffer.data(), static_cast<std::size_t>(n));
    sink.write(buffer.data(), static_cast<std::size_t>(n));
    done += static_cast<std::uint64_t>(n);
    advance(static_cast<std::uint64_t>(n));
    current = 1 - current;
  }
  hasher.wait();
  if (done != src.size) {
    hasher.finish();  // discard
    throwInputError(shown, "packing",
                    "changed size while it was being packed; make sure nothing writes to the "
                    "capture, then pack again");
  }
  sink.end();
  const auto [sha256, sha512] = hasher.finish();
  PayloadDigest out{src.in->bagPath, done, sha256, sha512};
  if (!src.in->expectedSha256.empty() && src.in->expectedSha256 != out.sha256)
    throw PayloadChanged(src.in->bagPath, shown);
  return out;
}

}  // namespace

std::vector<PayloadFile> checkedPayload(const BagInput& input, std::uint64_t& total) {
  std::vector<PayloadFile> sources;
  std::set<std::string> seen;
  total = 0;
  for (const PayloadSource& p : input.payload) {
    if (p.bagPath.rfind("data/", 0) != 0 || !safeRelative(p.bagPath)) {
      throw Error(ErrorKind::Internal, p.bagPath, "packing",
                  "is not a valid payload path (must be under data/, without '..')");
    }
    if (!seen.insert(p.bagPath).second) {
      throw Error(ErrorKind::Internal, p.bagPath, "packing", "is listed twice in the payload");
    }
    struct stat st {};
    if (::lstat(p.source.c_str(), &st) != 0) {
      throwInputError(p.source.string(), "packing",
                      std::string("cannot be read (") + std::strerror(errno) +
                          "); it is listed in the capture but missing or inaccessible");
    }
    if (!S_ISREG(st.st_mode)) {
      throwInputError(p.source.string(), "packing",
                      "is not a regular file (a link, folder or device); replace it with the "
                      "file itself");
    }
    sources.push_back({&p, static_cast<std::uint64_t>(st.st_size)});
    total += static_cast<std::uint64_t>(st.st_size);
  }
  std::sort(sources.begin(), sources.end(),
            [](const PayloadFile& a, const PayloadFile& b) { return a.in->bagPath < b.in->bagPath; });
  return sources;
}

std::vector<PayloadDigest> streamPayload(const BagInput& input, const std::vector<PayloadFile>& files,
                                         std::uint64_t total, Sink& sink) {
  std::vector<unsigned char> buffers[2] = {std::vector<unsigned char>(kBufferSize),
                                           std::vector<unsigned char>(kBufferSize)};
  PayloadHasher hasher;
  std::uint64_t done = 0;
  auto advance = [&](std::uint64_t n) {
    done += n;
    if (input.progress) input.progress(done, total);
  };
  std::vector<PayloadDigest> digests;
  digests.reserve(files.size());
  for (const PayloadFile& f : files) digests.push_back(streamFile(f, sink, hasher, buffers, advance));
  return digests;
}

}  // namespace surrogate::archive
