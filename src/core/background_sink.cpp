#include "core/background_sink.h"

#include <utility>

namespace surrogate {

BackgroundSink::BackgroundSink(Consumer consumer, std::size_t blockSize, std::size_t blocksWaiting)
    : consumer_(std::move(consumer)),
      blockSize_(blockSize ? blockSize : 1),
      blocksWaiting_(blocksWaiting ? blocksWaiting : 1),
      inline_(std::thread::hardware_concurrency() < 2) {
  if (!inline_) worker_ = std::thread([this] { consume(); });
}

BackgroundSink::~BackgroundSink() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

void BackgroundSink::consume() {
  while (true) {
    std::string block;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return stopped_ || closed_ || !waiting_.empty(); });
      if (stopped_ || (waiting_.empty() && closed_)) return;
      block = std::move(waiting_.front());
      waiting_.pop_front();
    }
    changed_.notify_all();  // room in the queue
    try {
      consumer_(block.data(), block.size());
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      failure_ = std::current_exception();
      stopped_ = true;
      waiting_.clear();
      changed_.notify_all();
      return;
    }
  }
}

void BackgroundSink::rethrowFailure() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (failure_) std::rethrow_exception(failure_);
}

void BackgroundSink::push(std::string&& block) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return stopped_ || waiting_.size() < blocksWaiting_; });
  if (failure_) std::rethrow_exception(failure_);
  if (stopped_) return;
  waiting_.push_back(std::move(block));
  lock.unlock();
  changed_.notify_all();
}

void BackgroundSink::write(const char* data, std::size_t size) {
  if (inline_) {
    consumer_(data, size);
    return;
  }
  while (size > 0) {
    const std::size_t n = std::min(size, blockSize_ - filling_.size());
    filling_.append(data, n);
    data += n;
    size -= n;
    if (filling_.size() == blockSize_) {
      std::string full;
      full.reserve(blockSize_);
      full.swap(filling_);
      push(std::move(full));
    }
  }
  rethrowFailure();
}

void BackgroundSink::finish() {
  if (inline_ || !worker_.joinable()) return;
  if (!filling_.empty()) push(std::move(filling_));
  filling_.clear();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
  worker_.join();
  rethrowFailure();
}

}  // namespace surrogate
