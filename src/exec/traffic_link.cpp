#include "traffic_link.h"

#include <fmt/format.h>

#include <optional>
#include <string_view>
#include <utility>

namespace rondo::exec {

TrafficLink::TrafficLink(Clock& clock, traffic::Reservations& reservations, std::vector<TrafficWait>& waits,
                         std::string robot)
    : clock_(clock), reservations_(reservations), waits_(waits), robot_(std::move(robot)) {}

TrafficLink::~TrafficLink() {
  alive_.reset();
  if (joined_) reservations_.leave(id_);
}

void TrafficLink::join(map::NodeIndex at) {
  if (joined_) return;
  id_ = reservations_.join(robot_, at, this);
  joined_ = true;
}

std::size_t TrafficLink::request(const void* owner, map::NodeIndex here, std::span<const map::EdgeIndex> route,
                                 int rank) {
  if (!joined_) join(here);
  if (owner_ != owner) {
    clear_ = nullptr;
    aside_ = nullptr;
  }
  owner_ = owner;
  reservations_.set_parked(id_, false);  // it moves
  reservations_.set_rank(id_, rank);
  return reservations_.request(id_, here, route);
}

void TrafficLink::set_parked(bool parked) {
  if (joined_) reservations_.set_parked(id_, parked);
}

void TrafficLink::decline(const traffic::MakeWay& make_way) {
  if (joined_ && reservations_.granted(id_) == make_way.route) reservations_.stop(id_, reservations_.at(id_));
}

void TrafficLink::crossed(map::EdgeIndex edge) {
  if (joined_) reservations_.crossed(id_, edge);
}

void TrafficLink::stop(const void* owner, map::NodeIndex here) {
  if (!joined_ || (owner_ != nullptr && owner_ != owner)) return;
  clear_ = nullptr;
  aside_ = nullptr;
  reservations_.stop(id_, here);
}

void TrafficLink::forget(const void* owner) {
  if (owner_ != owner) return;
  owner_ = nullptr;
  clear_ = nullptr;
  aside_ = nullptr;
}

void TrafficLink::when_waiting(const void* owner, std::function<void()> clear,
                               std::function<void(const traffic::MakeWay&)> aside) {
  owner_ = owner;
  clear_ = std::move(clear);
  aside_ = std::move(aside);
}

void TrafficLink::wait_began(map::NodeIndex at, Time now) {
  if (wait_) return;
  TrafficWait w{.robot = robot_, .node = reservations_.map().node(at).name, .start = now};
  wait_at_ = at;
  for (traffic::RobotId b : reservations_.waits_for(id_)) w.behind.push_back(reservations_.name(b));
  wait_ = waits_.size();
  waits_.push_back(std::move(w));
}

void TrafficLink::wait_ended(Time now, const char* how) {
  if (!wait_) return;
  waits_[*wait_].end = now;
  waits_[*wait_].how = how;
  if (std::string_view(how) == "passed") waited_ = std::make_pair(wait_at_, now - waits_[*wait_].start);
  wait_.reset();
}

Duration TrafficLink::take_waited(map::NodeIndex from) {
  if (!waited_ || waited_->first != from) return Duration{0};
  return std::exchange(waited_, std::nullopt)->second;
}

std::string TrafficLink::names(const std::vector<traffic::RobotId>& robots) const {
  std::string out;
  for (traffic::RobotId r : robots) out += (out.empty() ? "" : ", ") + reservations_.name(r);
  return out;
}

std::string TrafficLink::behind_text() const {
  std::string out;
  const map::TopoMap& m = reservations_.map();
  for (traffic::RobotId r : reservations_.waits_for(id_))
    out +=
        fmt::format("{}{} (at {})", out.empty() ? "" : ", ", reservations_.name(r), m.node(reservations_.at(r)).name);
  return out.empty() ? "nobody now" : out;
}

void TrafficLink::on_way_may_be_clear() {
  clock_.post([this, alive = std::weak_ptr<bool>(alive_)] {
    if (alive.expired()) return;  // the link is gone
    if (clear_) {
      auto clear = clear_;  // may replace itself
      clear();
    }
  });
}

void TrafficLink::on_make_way(const traffic::MakeWay& make_way) {
  clock_.post([this, make_way, alive = std::weak_ptr<bool>(alive_)] {
    if (alive.expired()) return;  // the link is gone
    if (aside_) {
      auto aside = aside_;
      aside(make_way);
    } else if (make_way.why == traffic::MakeWay::Why::kParked && parked_aside_) {
      parked_aside_(make_way);
    } else {  // nobody waits here any more: not driven
      decline(make_way);
    }
  });
}

}  // namespace rondo::exec
