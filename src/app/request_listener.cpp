#include "request_listener.h"

#include <fmt/format.h>

#include <chrono>
#include <ostream>

namespace rondo::app {

Result<std::unique_ptr<RequestListener>> RequestListener::start(exec::Clock& clock, RequestIntake& intake,
                                                                const store::StoreLocation& location,
                                                                std::ostream& log) {
  RONDO_ASSIGN_OR_RETURN(std::unique_ptr<store::RequestWatch> watch, store::RequestWatch::open(location));
  return std::unique_ptr<RequestListener>(new RequestListener(clock, intake, location, log, std::move(watch)));
}

RequestListener::RequestListener(exec::Clock& clock, RequestIntake& intake, store::StoreLocation location,
                                 std::ostream& log, std::unique_ptr<store::RequestWatch> watch)
    : clock_(clock), intake_(intake), location_(std::move(location)), log_(log), watch_(std::move(watch)) {
  thread_ = std::thread([this] { run(); });
}

RequestListener::~RequestListener() {
  stopping_ = true;
  {
    const std::lock_guard lock(watch_mutex_);
    if (watch_) watch_->stop();
  }
  stopped_.notify_all();
  thread_.join();
}

void RequestListener::run() {
  while (!stopping_) {
    const Result<bool> told = watch_->wait(seconds(60));
    if (told && *told) {
      clock_.post([this] { (void)intake_.take_waiting(); });  // a queue that cannot be read: the poll reads it later
    } else if (!told) {
      log_ << fmt::format("rondo serve: {}\n", told.error().message) << std::flush;
      if (!reopen()) return;
      clock_.post([this] { (void)intake_.take_waiting(); });  // what was queued while the watch was away
    }
  }
}

bool RequestListener::reopen() {
  while (!stopping_) {
    auto watch = store::RequestWatch::open(location_);
    if (watch) {
      const std::lock_guard lock(watch_mutex_);
      if (stopping_) return false;
      watch_ = std::move(*watch);
      return true;
    }
    std::unique_lock lock(watch_mutex_);
    stopped_.wait_for(lock, std::chrono::seconds(1), [this] { return stopping_.load(); });
  }
  return false;
}

}  // namespace rondo::app
