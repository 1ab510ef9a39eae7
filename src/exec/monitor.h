// A step's watchdog (MISSION.md §3 monitors): fires once past `factor` x the expected time +
// slack, unless cancelled first. While the robot is in fault it stands still, and on resume it runs
// on with the time it had left.
//
//   Monitor m(clock);
//   m.arm(Monitor::limit("navigation overrun: still travelling", "the expected travel time",
//                        expected, 2.0, seconds(60)), [](const std::string& why) { ... });
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "rondo/exec/clock.h"

namespace rondo::exec {

class Monitor {
 public:
  struct Limit {
    Duration after{0};
    std::string reason;  // what it says when it fires
  };
  // "<what> after 6 min, the limit is 2 x <of> 3 min + 1 min"
  static Limit limit(const char* what, const char* of, Duration expected, double factor, Duration slack);

  explicit Monitor(Clock& clock) : clock_(clock) {}
  ~Monitor() { cancel(); }
  Monitor(const Monitor&) = delete;
  Monitor& operator=(const Monitor&) = delete;

  void arm(Limit limit, std::function<void(const std::string&)> fired);
  // From inside `fired`: the monitor runs on to a new limit with the same callback.
  void extend(Limit limit);
  void cancel();
  void suspend();
  void resume();
  // When it fires, while it runs (not cancelled, fired or suspended).
  std::optional<Time> deadline() const;
  const std::string& reason() const { return reason_; }

 private:
  void set(Duration after);

  Clock& clock_;
  TimerId timer_ = 0;
  Time at_{};                    // when it fires
  std::optional<Duration> left_;  // while suspended: the time it still had
  std::string reason_;
  std::function<void(const std::string&)> fired_;
};

}  // namespace rondo::exec
