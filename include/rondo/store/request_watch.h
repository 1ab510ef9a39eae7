// Being told that a request was queued, instead of polling the queue (requests.h). On PostgreSQL
// queue_request() sends a NOTIFY on the channel `rondo_requests` in the transaction that queues
// the request (delivered when it commits), and a RequestWatch LISTENs on a connection of its own.
// SQLite has no notifications: open() returns kUnsupported there, and the reader polls.
//
//   auto watch = store::RequestWatch::open(db.location());
//   while (running)
//     if (auto told = (*watch)->wait(seconds(30)); told && *told) take_waiting();
//   // from another thread: (*watch)->stop() ends a wait at once
#pragma once

#include <atomic>
#include <memory>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

class RequestWatch {
 public:
  // Errors: kUnsupported (an SQLite store), kInvalidInput (cannot connect), kStorage (LISTEN failed).
  static Result<std::unique_ptr<RequestWatch>> open(const StoreLocation& location);
  virtual ~RequestWatch() = default;

  // Blocks until a request is queued (true), `timeout` passes (false) or stop() is called (false).
  // Notifications that came while nobody waited are not lost: the next wait returns at once.
  // kStorage when the connection is lost (the caller polls, and may open a new watch).
  virtual Result<bool> wait(Duration timeout) = 0;
  // Ends the wait in progress and every later one; safe from any thread.
  virtual void stop() = 0;
};

}  // namespace rondo::store
