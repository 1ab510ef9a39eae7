// The test's stand-in for the clock's thread-safe post(): closures from the MQTT threads are
// queued and run on the test's thread while it waits for a condition with a deadline.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>

#include "rondo/vda5050/mqtt_client.h"

namespace rondo::vda5050::testing {

class EventQueue {
 public:
  Post poster() {
    return [this](std::function<void()> f) {
      {
        std::lock_guard lock(mutex_);
        queue_.push_back(std::move(f));
      }
      cv_.notify_all();
    };
  }

  // Closures posted and not run yet.
  std::size_t pending() {
    std::lock_guard lock(mutex_);
    return queue_.size();
  }

  // Runs queued closures until `done()` holds (checked after each) or the deadline passes.
  bool run_until(const std::function<bool()>& done, std::chrono::milliseconds deadline) {
    const auto end = std::chrono::steady_clock::now() + deadline;
    for (;;) {
      if (done()) return true;
      std::function<void()> f;
      {
        std::unique_lock lock(mutex_);
        if (!cv_.wait_until(lock, end, [&] { return !queue_.empty(); })) return done();
        f = std::move(queue_.front());
        queue_.pop_front();
      }
      f();
    }
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> queue_;
};

}  // namespace rondo::vda5050::testing
