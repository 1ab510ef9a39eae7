// `rondo serve` on a PostgreSQL store: requests that `rondo task add --store` queues are taken as
// soon as they are committed, not at the next poll. A thread of its own waits on a
// store::RequestWatch (LISTEN/NOTIFY) and posts RequestIntake::take_waiting() to the clock's thread
// at each notification. If the watch's connection is lost it opens a new one (and takes what came
// meanwhile); the intake's slow poll covers the time between.
//
//   RequestIntake intake(clock, executor, db);
//   auto listener = RequestListener::start(clock, intake, db.location(), log);  // PostgreSQL only
//   ...                                                    // its destructor stops and joins the thread
#pragma once

#include <atomic>
#include <condition_variable>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <thread>

#include "request_intake.h"
#include "rondo/store/request_watch.h"
#include "rondo/store/store.h"

namespace rondo::app {

class RequestListener {
 public:
  // Errors: kUnsupported (an SQLite store), or the watch's first open failing. Precondition: the
  // clock and the intake outlive the listener.
  static Result<std::unique_ptr<RequestListener>> start(exec::Clock& clock, RequestIntake& intake,
                                                        const store::StoreLocation& location, std::ostream& log);
  ~RequestListener();
  RequestListener(const RequestListener&) = delete;
  RequestListener& operator=(const RequestListener&) = delete;

 private:
  RequestListener(exec::Clock& clock, RequestIntake& intake, store::StoreLocation location, std::ostream& log,
                  std::unique_ptr<store::RequestWatch> watch);
  void run();
  // A new watch after a lost connection, tried once a second until it opens or the listener stops.
  bool reopen();

  exec::Clock& clock_;
  RequestIntake& intake_;
  store::StoreLocation location_;
  std::ostream& log_;
  std::mutex watch_mutex_;  // stop() from the destructor against reopen() on the thread
  std::unique_ptr<store::RequestWatch> watch_;
  std::condition_variable stopped_;  // wakes reopen()'s wait between two tries
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace rondo::app
