#include "rondo/vda5050/connection_watch.h"

#include <algorithm>

namespace rondo::vda5050 {

void ConnectionWatch::on_connection(ConnectionState state, Time t) {
  announced_ = state;
  announced_at_ = t;
  broker_lost_.reset();
}

void ConnectionWatch::on_state(Time t) {
  last_state_ = t;
  broker_lost_.reset();
}

void ConnectionWatch::on_broker_lost(Time t) {
  broker_lost_ = t;
}

std::string ConnectionWatch::why_offline(Time now) const {
  if (broker_lost_) return "rondo lost the broker at " + format_time(*broker_lost_);
  if (!announced_ && !last_state_) return "the vehicle has not been heard from";
  const bool state_since_announcement = last_state_ && *last_state_ > announced_at_;
  if (announced_ && *announced_ != ConnectionState::kOnline && !(compat_.vda5050_lib_1_4 && state_since_announcement)) {
    return std::string("the vehicle's connection is ") + to_string(*announced_);
  }
  const Time heard = last_state_ ? std::max(*last_state_, announced_at_) : announced_at_;
  if (now - heard > offline_after_) {
    return "no state for " + format_duration(now - heard) + " (offline after " + format_duration(offline_after_) + ")";
  }
  return "";
}

}  // namespace rondo::vda5050
