// The executive's only source of time (DESIGN.md, Time). The executor never reads the wall clock
// and never sleeps: it asks a Clock for now() and for callbacks at later instants. SimClock is a
// discrete-event queue that jumps from one event to the next, so weeks of robot life run as fast
// as the CPU allows; SystemClock waits for the real time of each event (optionally X times faster).
//
//   SimClock clock(parse_time("2026-11-23T00:00:00Z").value());
//   clock.schedule_at(clock.now() + minutes(5), [&] { robot.traverse(edge); });
//   clock.run_until(clock.now() + days(1));       // runs every event due by then, in order
//
//   std::thread adapter([&] { clock.post([&] { executor.on_edge_finished(a); }); });  // any thread
//
// Events due at the same instant run in the order they were scheduled. A callback may schedule
// and cancel other events. One thread owns a clock and runs its events: schedule_at(), cancel()
// and the run functions belong to it. post() and (SystemClock) stop() may be called from any
// thread, e.g. a robot adapter's, an HTTP server's or a signal handler's helper thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "rondo/core/time.h"

namespace rondo::exec {

using TimerId = std::uint64_t;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual Time now() const = 0;
  // Runs `callback` at `at` (at once, on the next step, when `at` is not after now()). Returns an
  // id for cancel().
  virtual TimerId schedule_at(Time at, std::function<void()> callback) = 0;
  // Forgets a pending event; does nothing when it already ran or was cancelled.
  virtual void cancel(TimerId id) = 0;
  // Thread-safe: runs `callback` on the clock's thread as soon as it can (before the next timed
  // event), waking a clock that is waiting. Posted callbacks run in the order they were posted.
  virtual void post(std::function<void()> callback) = 0;
  TimerId schedule_after(Duration delay, std::function<void()> callback) {
    return schedule_at(now() + delay, std::move(callback));
  }
};

// The event queue shared by both clocks: pending callbacks ordered by (time, sequence).
class EventQueue {
 public:
  TimerId push(Time at, std::function<void()> callback);
  void cancel(TimerId id);
  bool empty() const { return events_.empty(); }
  // The time of the earliest pending event. Precondition: !empty().
  Time next_time() const;
  // Removes and returns the earliest event's callback. Precondition: !empty().
  std::function<void()> pop();
  std::size_t size() const { return events_.size(); }
  void clear() {
    events_.clear();
    due_.clear();
  }

 private:
  struct Key {
    Time at;
    TimerId id;
    auto operator<=>(const Key&) const = default;
  };
  std::map<Key, std::function<void()>> events_;
  std::map<TimerId, Time> due_;  // id -> time, for cancel()
  TimerId next_id_ = 1;
};

// Callbacks posted from other threads, waiting for the clock's thread. Thread-safe.
class PostBox {
 public:
  // Adds a callback; returns true when the box was empty before (the owner may need waking).
  bool put(std::function<void()> callback);
  // Takes every callback posted so far, in posting order.
  std::vector<std::function<void()>> take();
  // Puts callbacks taken and not run back in front of those posted since, in their order.
  void put_back(std::vector<std::function<void()>> callbacks);
  bool empty() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::function<void()>> callbacks_;
};

// Simulated time: now() moves only when an event runs. Posted callbacks run at the current time,
// before the next timed event.
class SimClock final : public Clock {
 public:
  explicit SimClock(Time start) : now_(start) {}
  Time now() const override { return now_; }
  TimerId schedule_at(Time at, std::function<void()> callback) override;
  void cancel(TimerId id) override { queue_.cancel(id); }
  void post(std::function<void()> callback) override { (void)posted_.put(std::move(callback)); }
  // Runs the posted callbacks, or else the earliest pending event (moving now() to its time).
  // False when nothing is pending.
  bool step();
  // Runs every event due at or before `end`, then sets now() to `end`.
  void run_until(Time end);
  std::size_t pending() const { return queue_.size(); }
  // Drops every pending event and posted callback (a test's kill: the timers of an executive that
  // died go with it; now() stays).
  void clear() {
    queue_.clear();
    (void)posted_.take();
  }

 private:
  bool run_posted();
  Time now_;
  EventQueue queue_;
  PostBox posted_;
};

// Real time (`rondo run --realtime`, `rondo serve`): run_until() waits until each event is due.
// The only place in rondo that reads the system clock for the executive.
// - now() is UTC: the system clock, or with speed X, the UTC time at construction plus X times the
//   (monotonic) time elapsed since.
// - Timers run on the monotonic clock: schedule_at(t) fires (t - now()) / X of monotonic time after
//   the call, so a step of the wall clock (NTP, a person setting the time) neither fires nor
//   delays a pending timer. Event times stay UTC.
// - The loop waits on a condition variable: post() and stop() wake it at once.
class SystemClock final : public Clock {
 public:
  using Steady = std::chrono::steady_clock;
  // Where the clock reads time; tests give their own to step the wall clock.
  struct Sources {
    std::function<Time()> wall;
    std::function<Steady::time_point()> steady;
  };
  static Sources system_sources();

  // Precondition: speed > 0 (and finite).
  explicit SystemClock(double speed = 1.0, Sources sources = system_sources());
  Time now() const override;
  TimerId schedule_at(Time at, std::function<void()> callback) override;
  void cancel(TimerId id) override { queue_.cancel(id); }
  void post(std::function<void()> callback) override;

  // Runs events as they fall due until now() reaches `end` or stop() is called.
  void run_until(Time end);
  // Thread-safe: makes run_until() return after the callback it is running, if any; callbacks
  // posted and not run yet stay posted (run_due() runs them; the destructor drops them).
  void stop();
  bool stopped() const;
  // Runs the posted callbacks and every timer due by the monotonic clock now, without waiting.
  // Returns how many ran (for tests and for loops that wait elsewhere).
  std::size_t run_due();
  double speed() const { return speed_; }

 private:
  Steady::time_point steady_now() const { return sources_.steady(); }
  static Time as_key(Steady::time_point t) { return Time{std::chrono::duration_cast<Duration>(t.time_since_epoch())}; }

  double speed_;
  Sources sources_;
  Time wall_start_;
  Steady::time_point steady_start_;
  EventQueue queue_;  // keyed by the monotonic deadline
  PostBox posted_;
  mutable std::mutex wake_mutex_;
  std::condition_variable wake_;
  bool stop_ = false;  // under wake_mutex_
};

}  // namespace rondo::exec
