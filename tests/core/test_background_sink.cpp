// BackgroundSink (core/background_sink.h): the consumer sees every byte in order on its own
// thread, its failure stops the maker, and a slow consumer holds the maker back instead of
// letting blocks pile up.
#include <atomic>
#include <chrono>
#include <future>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include <catch2/catch.hpp>

#include "core/background_sink.h"

using surrogate::BackgroundSink;

namespace {

std::string randomText(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::string s(n, '\0');
  for (char& c : s) c = static_cast<char>(rng() & 0xff);
  return s;
}

}  // namespace

TEST_CASE("BackgroundSink hands every byte over, in order, in pieces of any size") {
  const std::string text = randomText(3'000'017, 1);
  std::string seen;
  std::thread::id consumerThread;
  {
    BackgroundSink sink(
        [&](const char* p, std::size_t n) {
          consumerThread = std::this_thread::get_id();
          seen.append(p, n);
        },
        /*blockSize=*/4093, /*blocksWaiting=*/2);
    std::mt19937 rng(2);
    std::size_t at = 0;
    while (at < text.size()) {
      const std::size_t n = std::min<std::size_t>(text.size() - at, rng() % 9000);  // 0 included
      sink.write(text.data() + at, n);
      at += n;
    }
    sink.finish();
  }
  CHECK(seen.size() == text.size());
  CHECK(seen == text);
  if (std::thread::hardware_concurrency() >= 2) CHECK(consumerThread != std::this_thread::get_id());
}

TEST_CASE("BackgroundSink rethrows the consumer's exception to the maker and stops early") {
  const std::string piece(1000, 'x');
  std::size_t consumed = 0;
  BackgroundSink sink(
      [&](const char*, std::size_t n) {
        consumed += n;
        if (consumed > 10'000) throw std::runtime_error("the validator gave up");
      },
      /*blockSize=*/1000, /*blocksWaiting=*/2);
  std::size_t written = 0;
  bool thrown = false;
  try {
    for (int i = 0; i < 100'000; ++i) {
      sink.write(piece.data(), piece.size());
      written += piece.size();
    }
    sink.finish();
  } catch (const std::runtime_error& e) {
    thrown = true;
    CHECK(std::string(e.what()) == "the validator gave up");
  }
  CHECK(thrown);
  // Once the consumer failed, the maker learns it at its next write: it cannot have gone on
  // to the end of a long text.
  CHECK(written < 1'000'000);
}

TEST_CASE("BackgroundSink holds a fast maker back while the consumer is busy") {
  if (std::thread::hardware_concurrency() < 2) return;  // the consumer runs inline there
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<std::size_t> handedOver{0};
  std::string seen;
  BackgroundSink sink(
      [&](const char* p, std::size_t n) {
        released.wait();
        seen.append(p, n);
      },
      /*blockSize=*/100, /*blocksWaiting=*/3);
  std::thread maker([&] {
    const std::string piece(10, 'y');
    for (int i = 0; i < 1000; ++i) {
      sink.write(piece.data(), piece.size());
      handedOver += piece.size();
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // One block in the consumer's hands, three waiting, one being filled: nothing more.
  CHECK(handedOver.load() <= 5 * 100);
  release.set_value();
  maker.join();
  sink.finish();
  CHECK(seen == std::string(10'000, 'y'));
}

TEST_CASE("BackgroundSink left without finish (the maker failed) stops its consumer") {
  std::atomic<std::size_t> consumed{0};
  {
    BackgroundSink sink([&](const char*, std::size_t n) { consumed += n; }, 64, 2);
    const std::string piece(1000, 'z');
    sink.write(piece.data(), piece.size());
  }  // no hang, no crash: what waited is dropped
  CHECK(consumed.load() <= 1000);
}
