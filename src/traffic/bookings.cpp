#include "rondo/traffic/bookings.h"

#include <algorithm>

namespace rondo::traffic {

namespace {

// A stop overlaps [t, t + length): an instant (length 0) at t overlaps a stop that holds t.
bool overlaps(const Stop& s, Time t, Duration length) {
  const Time end = t + std::max(length, Duration{1});
  return s.from < end && t < s.to;
}

}  // namespace

Time earliest_free(const std::vector<Stop>& stops, int capacity, Time at, Duration length) {
  // Going left from a free start, the stops overlapping can only grow where a stop ends: the
  // earliest free start is `at` or the end of a stop.
  std::vector<Time> candidates{at};
  for (const Stop& s : stops)
    if (s.to > at) candidates.push_back(s.to);
  std::sort(candidates.begin(), candidates.end());
  for (const Time t : candidates) {
    int in = 0;
    for (const Stop& s : stops) in += overlaps(s, t, length) ? 1 : 0;
    if (in < capacity) return t;
  }
  return candidates.back();  // not reached: past every stop's end none overlaps
}

Bookings::Bookings(const map::TopoMap& map) : capacity_(map.node_count(), 1), at_node_(map.node_count()) {
  for (map::NodeIndex n = 0; n < map.node_count(); ++n) capacity_[n] = std::max(1, map.node(n).capacity);
}

void Bookings::set_capacity(map::NodeIndex node, int capacity) {
  capacity_.at(node) = std::max(1, capacity);
}

BookingRobot Bookings::join(std::string name) {
  names_.push_back(std::move(name));
  booked_.emplace_back();
  calls_.emplace_back();
  return names_.size() - 1;
}

void Bookings::publish(BookingRobot robot, std::vector<Booking> bookings) {
  std::erase_if(bookings, [](const Booking& b) { return b.to <= b.from; });
  const auto changed = [&](const Booking& b, const std::vector<Booking>& in) {
    return std::find(in.begin(), in.end(), b) == in.end();
  };
  std::vector<map::NodeIndex> nodes;
  for (const Booking& b : booked_.at(robot))
    if (b.committed && changed(b, bookings)) nodes.push_back(b.node);
  for (const Booking& b : bookings)
    if (b.committed && changed(b, booked_[robot])) nodes.push_back(b.node);
  for (const Booking& b : booked_[robot])
    std::erase_if(at_node_.at(b.node), [robot](const Entry& e) { return e.robot == robot; });
  for (const Booking& b : bookings) at_node_.at(b.node).push_back({robot, b});
  booked_[robot] = std::move(bookings);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  for (const map::NodeIndex n : nodes) {
    std::vector<BookingRobot> told;
    for (const Entry& e : at_node_[n])
      if (e.robot != robot && calls_[e.robot] && std::find(told.begin(), told.end(), e.robot) == told.end())
        told.push_back(e.robot);
    for (const BookingRobot r : told) calls_[r](n);
  }
}

std::vector<Stop> Bookings::gives_way_at(BookingRobot robot, map::NodeIndex node) const {
  std::vector<Stop> stops;
  for (const Entry& e : at_node_.at(node))
    if (gives_way(robot, e)) stops.push_back({e.robot, e.booking.from, e.booking.to});
  return stops;
}

Time Bookings::earliest(BookingRobot robot, map::NodeIndex node, Time at, Duration length) const {
  if (at_node_.at(node).empty()) return at;
  return earliest_free(gives_way_at(robot, node), capacity_.at(node), at, length);
}

std::optional<Stop> Bookings::behind(BookingRobot robot, map::NodeIndex node, Time at, Duration length) const {
  const std::vector<Stop> stops = gives_way_at(robot, node);
  const Time free = earliest_free(stops, capacity_.at(node), at, length);
  if (free == at) return std::nullopt;
  std::optional<Stop> last;
  for (const Stop& s : stops)
    if (s.to <= free && s.to > at && overlaps(s, at, free - at + length) && (!last || s.to > last->to)) last = s;
  return last;
}

}  // namespace rondo::traffic
