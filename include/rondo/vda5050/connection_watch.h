// Whether the vehicle is there: its retained `connection` topic (ONLINE, OFFLINE,
// CONNECTIONBROKEN) and the age of its last state. A vehicle silent for longer than
// `offline_after` counts as offline even when no last will came. Pure: time is an argument.
//
//   ConnectionWatch watch(seconds(30), compat);
//   watch.on_connection(ConnectionState::kOnline, t);
//   watch.on_state(t2);
//   if (!watch.online(now)) fault(watch.why_offline(now));
//
// With Compatibility::vda5050_lib_1_4, a state that arrives after OFFLINE or CONNECTIONBROKEN
// counts as the vehicle being back (vda-5050-lib 1.4.0 does not republish ONLINE after it
// reconnects by itself); without it, only ONLINE brings the vehicle back.
#pragma once

#include <optional>
#include <string>

#include "rondo/core/time.h"
#include "rondo/vda5050/compat.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

class ConnectionWatch {
 public:
  ConnectionWatch(Duration offline_after, Compatibility compat) : offline_after_(offline_after), compat_(compat) {}

  void on_connection(ConnectionState state, Time t);
  void on_state(Time t);
  // rondo's own connection to the broker dropped: nothing is known until it is back.
  void on_broker_lost(Time t);

  bool online(Time now) const { return why_offline(now).empty(); }
  // "" when online; else why not, e.g. "no state for 42s (offline after 30s)".
  std::string why_offline(Time now) const;

 private:
  Duration offline_after_;
  Compatibility compat_;
  std::optional<ConnectionState> announced_;
  Time announced_at_{};
  std::optional<Time> last_state_;
  std::optional<Time> broker_lost_;
};

}  // namespace rondo::vda5050
