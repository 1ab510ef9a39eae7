// Where each robot of the building plans to stop, and when (docs/traffic.md, "Planning around each
// other"): the places of its scheduled and running tasks, each for the time its schedule gives it.
// A robot plans around the others' stops (prioritised planning in time): it does not plan to stop
// at a node while the robots it gives way to fill it, and its schedule and its departures move
// past them, so that it waits where it stands rather than in front of a taken counter or room.
//
//   Bookings b(map);
//   RobotId r1 = b.join("r1"), r2 = b.join("r2");      // r1 joined first: r2 gives way to its plan
//   b.publish(r1, {{.node = pharmacy, .from = t0, .to = t0 + minutes(2)}});
//   Time t = b.earliest(r2, pharmacy, t0, minutes(1));  // t0 + 2 min: after r1 has left
//
// Which stops a robot gives way to: every committed one (a running task's: that robot has set out
// and plans no more), and the planned ones of the robots that joined before it. So a robot never
// waits, through bookings, for one that waits for it: the committed never wait, and among the
// planned the order of joining decides. A node holds `capacity` robots (the map's), as in the
// reservations; a robot passing a node books nothing (the reservations see to passing).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::traffic {

using BookingRobot = std::size_t;

// One planned stop: the robot at `node` over [from, to).
struct Booking {
  map::NodeIndex node = 0;
  Time from{};
  Time to{};
  bool committed = false;  // a running task's: everyone gives way to it
  bool operator==(const Booking&) const = default;
};

// A stop of another robot that one robot gives way to.
struct Stop {
  BookingRobot robot = 0;
  Time from{};
  Time to{};
  bool operator==(const Stop&) const = default;
};

// The earliest t >= at at which [t, t + length) overlaps fewer than `capacity` of `stops` (a
// length of 0 counts as an instant). The answer never decreases as `at` grows.
Time earliest_free(const std::vector<Stop>& stops, int capacity, Time at, Duration length);

class Bookings {
 public:
  // Node capacities from the map (a node's `capacity`, at least 1).
  explicit Bookings(const map::TopoMap& map);
  Bookings(const Bookings&) = delete;
  Bookings& operator=(const Bookings&) = delete;

  void set_capacity(map::NodeIndex node, int capacity);
  int capacity(map::NodeIndex node) const { return capacity_.at(node); }

  // A robot joins with nothing booked; those who joined before it go first.
  BookingRobot join(std::string name);
  const std::string& name(BookingRobot robot) const { return names_.at(robot); }
  std::size_t robot_count() const { return names_.size(); }

  // The robot's stops, all of them: replaces what it published before. Empty: it plans none.
  // Every other robot with a stop at a node where a committed stop came or went is told
  // (`on_changed`): it may have to set out later, or may set out sooner.
  void publish(BookingRobot robot, std::vector<Booking> bookings);
  // Called with a node where another robot's stops changed and this robot has one; may be empty.
  // It must not publish from inside the call (post it).
  void on_changed(BookingRobot robot, std::function<void(map::NodeIndex)> call) { calls_.at(robot) = std::move(call); }
  const std::vector<Booking>& booked(BookingRobot robot) const { return booked_.at(robot); }

  // The stops at `node` that `robot` gives way to, in no particular order.
  std::vector<Stop> gives_way_at(BookingRobot robot, map::NodeIndex node) const;
  // The earliest t >= at at which `robot` may stop at `node` for `length`.
  Time earliest(BookingRobot robot, map::NodeIndex node, Time at, Duration length) const;
  // Of the stops that keep `robot` from stopping at `node` at `at` for `length`, the one that ends
  // last before earliest(): whom it waits for (nothing: it need not wait).
  std::optional<Stop> behind(BookingRobot robot, map::NodeIndex node, Time at, Duration length) const;

 private:
  struct Entry {
    BookingRobot robot;
    Booking booking;
  };
  bool gives_way(BookingRobot robot, const Entry& e) const {
    return e.robot != robot && (e.booking.committed || e.robot < robot);
  }

  std::vector<int> capacity_;
  std::vector<std::string> names_;
  std::vector<std::vector<Booking>> booked_;                // per robot
  std::vector<std::function<void(map::NodeIndex)>> calls_;  // per robot
  std::vector<std::vector<Entry>> at_node_;                 // per node
};

}  // namespace rondo::traffic
