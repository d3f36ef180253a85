// BackgroundSink: hands the pieces of a text, as they are made, to a consumer that runs on a
// thread of its own, so that making a text (a stylesheet writing METS) and reading it (the
// schema validator, a digest) use two cores instead of taking turns on one.
//
// Pieces are gathered into blocks; at most `blocksWaiting` full blocks wait for the consumer,
// so memory stays bounded whatever the text's size. The consumer sees every byte, in order.
// On a machine with one core the consumer runs inline, in write().
//
//   BackgroundSink sink([&](const char* p, std::size_t n) { validator.feed(p, n); });
//   makeText([&](const char* p, std::size_t n) { sink.write(p, n); });
//   sink.finish();  // waits until the consumer has seen everything; rethrows its exception
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace surrogate {

class BackgroundSink {
 public:
  using Consumer = std::function<void(const char*, std::size_t)>;
  explicit BackgroundSink(Consumer consumer, std::size_t blockSize = std::size_t(1) << 20,
                          std::size_t blocksWaiting = 4);
  // Without finish() (an exception on the making side): stops the consumer and drops what
  // waits.
  ~BackgroundSink();
  BackgroundSink(const BackgroundSink&) = delete;
  BackgroundSink& operator=(const BackgroundSink&) = delete;

  // Rethrows the consumer's exception as soon as it is known, so that the maker stops early.
  void write(const char* data, std::size_t size);
  // Hands over what is left, waits for the consumer to finish, and rethrows its exception.
  void finish();

 private:
  void consume();
  void push(std::string&& block);  // waits while the queue is full
  void rethrowFailure();

  Consumer consumer_;
  std::size_t blockSize_, blocksWaiting_;
  bool inline_;
  std::string filling_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::string> waiting_;
  bool closed_ = false, stopped_ = false;
  std::exception_ptr failure_;
  std::thread worker_;
};

}  // namespace surrogate
