// One robot's end of the traffic manager (docs/traffic.md): the executor joins the building's
// Reservations with it, and the journey that moves the robot (NavigateStep) asks through it for
// the way ahead, waits when it is held by others, and is told when to ask again or to make way.
// The manager's calls arrive while another robot's call is still being answered, so the link
// posts them to the clock; a journey that has ended is never called (forget()).
//
//   TrafficLink link(clock, reservations, building.traffic_waits, "r1");
//   link.join(robot.location());
//   std::size_t n = link.request(this, here, route, rank);   // 0: wait for on_clear / on_aside
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/exec/executor_types.h"
#include "rondo/map/topo_map.h"
#include "rondo/traffic/reservations.h"

namespace rondo::exec {

class TrafficLink final : public traffic::ReservationListener {
 public:
  TrafficLink(Clock& clock, traffic::Reservations& reservations, std::vector<TrafficWait>& waits, std::string robot);
  ~TrafficLink() override;
  TrafficLink(const TrafficLink&) = delete;
  TrafficLink& operator=(const TrafficLink&) = delete;

  void join(map::NodeIndex at);
  bool joined() const { return joined_; }

  // `owner` (a journey) asks for `route` from `here`: how many of its first edges it holds now.
  std::size_t request(const void* owner, map::NodeIndex here, std::span<const map::EdgeIndex> route, int rank);
  void crossed(map::EdgeIndex edge);
  // The owner's journey stopped at `here`: everything ahead is released (not when another owns it).
  void stop(const void* owner, map::NodeIndex here);
  // The owner is gone: nothing of it is called again.
  void forget(const void* owner);
  // What the waiting owner is told: ask again; drive this granted route aside.
  void when_waiting(const void* owner, std::function<void()> clear, std::function<void(const traffic::MakeWay&)> aside);

  // Parked: idle, or waiting for a task's window, where it stands; asked to make way through
  // `parked_aside` (the executor's), when no journey of it waits.
  void set_parked(bool parked);
  void when_parked_asked(std::function<void(const traffic::MakeWay&)> parked_aside) {
    parked_aside_ = std::move(parked_aside);
  }
  // Gives up the way it was granted aside without driving it.
  void decline(const traffic::MakeWay& make_way);

  // The wait record (Building::traffic_waits): begun once per wait, ended once.
  void wait_began(map::NodeIndex at, Time now);
  void wait_ended(Time now, const char* how);
  bool in_wait() const { return wait_.has_value(); }
  // The last wait that ended with the way granted, taken by the first attempt from where it
  // waited (the traversal log keeps it apart from the attempt's duration); 0 otherwise.
  Duration take_waited(map::NodeIndex from);
  // "r2 (at Main-05)": who holds the way it waits for.
  std::string behind_text() const;
  std::string names(const std::vector<traffic::RobotId>& robots) const;
  const traffic::Reservations& reservations() const { return reservations_; }

  void on_way_may_be_clear() override;
  void on_make_way(const traffic::MakeWay& make_way) override;

 private:
  Clock& clock_;
  traffic::Reservations& reservations_;
  std::vector<TrafficWait>& waits_;
  std::string robot_;
  traffic::RobotId id_ = 0;
  bool joined_ = false;
  const void* owner_ = nullptr;
  std::function<void()> clear_;
  std::function<void(const traffic::MakeWay&)> aside_;
  std::function<void(const traffic::MakeWay&)> parked_aside_;
  std::optional<std::size_t> wait_;  // index into waits_
  map::NodeIndex wait_at_ = 0;
  std::optional<std::pair<map::NodeIndex, Duration>> waited_;  // passed: where, how long
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace rondo::exec
