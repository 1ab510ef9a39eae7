// The executive's only source of time (DESIGN.md, Time). The executor never reads the wall clock
// and never sleeps: it asks a Clock for now() and for callbacks at later instants. SimClock is a
// discrete-event queue that jumps from one event to the next, so weeks of robot life run as fast
// as the CPU allows; SystemClock waits for the real time of each event.
//
//   SimClock clock(parse_time("2026-11-23T00:00:00Z").value());
//   clock.schedule_at(clock.now() + minutes(5), [&] { robot.traverse(edge); });
//   clock.run_until(clock.now() + days(1));       // runs every event due by then, in order
//
// Events due at the same instant run in the order they were scheduled. A callback may schedule
// and cancel other events. Not thread-safe: one thread owns the clock and runs its events.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <utility>

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

// Simulated time: now() moves only when an event runs.
class SimClock final : public Clock {
 public:
  explicit SimClock(Time start) : now_(start) {}
  Time now() const override { return now_; }
  TimerId schedule_at(Time at, std::function<void()> callback) override;
  void cancel(TimerId id) override { queue_.cancel(id); }
  // Runs the earliest pending event, moving now() to its time. False when none is pending.
  bool step();
  // Runs every event due at or before `end`, then sets now() to `end`.
  void run_until(Time end);
  std::size_t pending() const { return queue_.size(); }

 private:
  Time now_;
  EventQueue queue_;
};

// Real time (`rondo run --realtime`): run_until() sleeps until each event is due. The only place
// in rondo that reads the system clock for the executive.
class SystemClock final : public Clock {
 public:
  Time now() const override;
  TimerId schedule_at(Time at, std::function<void()> callback) override;
  void cancel(TimerId id) override { queue_.cancel(id); }
  void run_until(Time end);

 private:
  EventQueue queue_;
};

}  // namespace rondo::exec
