#include "rondo/traffic/reservations.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace rondo::traffic {
namespace {

constexpr std::size_t kNoPassage = std::numeric_limits<std::size_t>::max();

bool contains(const std::vector<RobotId>& v, RobotId r) {
  return std::find(v.begin(), v.end(), r) != v.end();
}

}  // namespace

const char* to_string(MakeWay::Why why) {
  return why == MakeWay::Why::kDeadlock ? "deadlock" : "parked";
}

Reservations::Reservations(const map::TopoMap& map, ReservationOptions options)
    : map_(map), options_(options), passage_of_(map.edge_count(), kNoPassage), node_holders_(map.node_count()) {
  if (options_.lookahead == 0) options_.lookahead = 1;
  capacity_.reserve(map.node_count());
  for (map::NodeIndex n = 0; n < map.node_count(); ++n) capacity_.push_back(std::max(1, map.node(n).capacity));
  std::map<std::pair<map::NodeIndex, map::NodeIndex>, std::size_t> passages;
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
    const map::Narrow mark = map::passage_narrow(map, e);
    if (mark == map::Narrow::kNone) continue;
    const map::NodeIndex a = map.from_index(e), b = map.to_index(e);
    const auto [it, added] = passages.try_emplace({std::min(a, b), std::max(a, b)}, passage_mark_.size());
    if (added) passage_mark_.push_back(mark);
    passage_of_[e] = it->second;
  }
  passage_holds_.resize(passage_mark_.size());
  // Dead ends: nodes whose every edge leads to and from one neighbour (rooms, counters, docks).
  dead_end_.assign(map.node_count(), false);
  for (map::NodeIndex n = 0; n < map.node_count(); ++n) {
    std::optional<map::NodeIndex> only;
    bool one = true;
    for (map::EdgeIndex e : map.out_edges(n)) {
      if (only && *only != map.to_index(e)) one = false;
      only = map.to_index(e);
    }
    for (map::EdgeIndex e : map.in_edges(n))
      if (only && *only != map.from_index(e)) one = false;
    dead_end_[n] = one && only.has_value();
  }
}

void Reservations::set_capacity(map::NodeIndex node, int capacity) {
  capacity_.at(node) = std::max(1, capacity);
}

RobotId Reservations::join(std::string name, map::NodeIndex at, ReservationListener* listener) {
  const RobotId id = robots_.size();
  robots_.push_back(Robot{.name = std::move(name), .listener = listener, .at = at});
  hold_node(id, at);
  return id;
}

void Reservations::leave(RobotId robot) {
  Robot& r = robots_.at(robot);
  if (!r.present) return;
  release_ahead(robot, 0);
  release_node(robot, r.at);
  r.present = false;
  r.waiting = false;
  r.blockers.clear();
  wake_waiting_on(robot);
  notify();
}

void Reservations::set_rank(RobotId robot, int rank) {
  robots_.at(robot).rank = rank;
}

void Reservations::set_parked(RobotId robot, bool parked) {
  Robot& r = robots_.at(robot);
  if (r.parked == parked) return;
  r.parked = parked;
  if (!parked) return;
  // Somebody may be waiting for it already.
  for (RobotId w = 0; w < robots_.size(); ++w) {
    if (!robots_[w].present || !robots_[w].waiting) continue;
    refresh_blockers(w);
    if (contains(robots_[w].blockers, robot)) {
      resolve_from(w);
      break;
    }
  }
  notify();
}

std::vector<RobotId> Reservations::passage_holders(map::EdgeIndex edge) const {
  std::vector<RobotId> out;
  if (passage(edge) == kNoPassage) return out;
  for (const PassageHold& h : passage_holds_[passage(edge)]) out.push_back(h.robot);
  return out;
}

std::vector<RobotId> Reservations::in_the_way(RobotId robot, map::EdgeIndex edge) const {
  std::vector<RobotId> way;
  const map::NodeIndex far = map_.to_index(edge);
  const std::vector<RobotId>& there = node_holders_[far];
  if (!contains(there, robot)) {
    if (static_cast<int>(there.size()) >= capacity_[far]) way = there;
  }
  if (const std::size_t p = passage(edge); p != kNoPassage) {
    const bool single = passage_mark_[p] == map::Narrow::kSingle;
    for (const PassageHold& h : passage_holds_[p])
      if (h.robot != robot && (single || h.forward != forward(edge)) && !contains(way, h.robot)) way.push_back(h.robot);
  }
  return way;
}

std::vector<RobotId> Reservations::unit_in_the_way(RobotId robot, std::span<const map::EdgeIndex> unit) const {
  std::vector<RobotId> way;
  for (map::EdgeIndex e : unit)
    for (RobotId b : in_the_way(robot, e))
      if (!contains(way, b)) way.push_back(b);
  return way;
}

std::size_t Reservations::unit_length(std::span<const map::EdgeIndex> route, std::size_t i) const {
  if (passage(route[i]) == kNoPassage) {
    // The way into a dead end is granted with the node in front of it: nobody queues there.
    if (i + 1 < route.size() && passage(route[i + 1]) == kNoPassage && dead_end_[map_.to_index(route[i + 1])]) return 2;
    return 1;
  }
  std::size_t j = i;
  while (j < route.size() && passage(route[j]) != kNoPassage) ++j;
  return j - i;
}

void Reservations::hold_node(RobotId robot, map::NodeIndex node) {
  node_holders_.at(node).push_back(robot);
}

void Reservations::release_node(RobotId robot, map::NodeIndex node) {
  std::vector<RobotId>& h = node_holders_.at(node);
  if (const auto it = std::find(h.begin(), h.end(), robot); it != h.end()) h.erase(it);
}

void Reservations::release_passage(RobotId robot, map::EdgeIndex edge) {
  if (passage(edge) == kNoPassage) return;
  std::vector<PassageHold>& h = passage_holds_[passage(edge)];
  if (const auto it = std::find_if(h.begin(), h.end(), [&](const PassageHold& x) { return x.robot == robot; });
      it != h.end())
    h.erase(it);
}

void Reservations::grant(RobotId robot, map::EdgeIndex edge) {
  hold_node(robot, map_.to_index(edge));
  if (passage(edge) != kNoPassage) passage_holds_[passage(edge)].push_back({robot, forward(edge)});
  robots_[robot].granted.push_back(edge);
}

void Reservations::release_ahead(RobotId robot, std::size_t keep) {
  Robot& r = robots_[robot];
  for (std::size_t i = keep; i < r.granted.size(); ++i) {
    release_node(robot, map_.to_index(r.granted[i]));
    release_passage(robot, r.granted[i]);
  }
  if (keep < r.granted.size()) r.granted.resize(keep);
}

std::size_t Reservations::request(RobotId robot, map::NodeIndex here, std::span<const map::EdgeIndex> route) {
  Robot& r = robots_.at(robot);
  if (!r.present) throw std::logic_error("Reservations::request: the robot has left");
  map::NodeIndex at = here;
  for (map::EdgeIndex e : route) {
    if (e >= map_.edge_count() || map_.from_index(e) != at)
      throw std::invalid_argument("Reservations::request: the route is not consecutive edges from the robot's node");
    at = map_.to_index(e);
  }
  const std::size_t before = r.granted.size();
  if (here != r.at) {  // carried, or stopped where nobody told us: it holds where it is
    release_ahead(robot, 0);
    release_node(robot, r.at);
    r.at = here;
    hold_node(robot, here);
  }
  std::size_t keep = 0;
  while (keep < r.granted.size() && keep < route.size() && r.granted[keep] == route[keep]) ++keep;
  release_ahead(robot, keep);
  const bool released = r.granted.size() < before;
  r.wanted.assign(route.begin(), route.end());
  const bool was_waiting = r.waiting;
  // A robot sent aside lets the robots it made way for go first: it waits while any of them waits.
  std::erase_if(r.yield_to, [&](RobotId o) { return !robots_[o].present || !robots_[o].waiting; });
  if (!r.yield_to.empty() && r.granted.empty() && !route.empty()) {
    start_waiting(robot, route[0], r.yield_to);
    if (released) wake_waiting_on(robot);
    notify();
    return 0;
  }
  std::vector<RobotId> way;
  std::size_t i = r.granted.size();
  while (i < route.size() && i < options_.lookahead) {
    const std::size_t n = unit_length(route, i);
    way = unit_in_the_way(robot, route.subspan(i, n));
    if (!way.empty()) break;
    for (std::size_t k = i; k < i + n; ++k) grant(robot, route[k]);
    i += n;
  }
  const std::size_t held = r.granted.size();  // of `route`: a resolution may send it aside instead
  if (r.granted.empty() && !route.empty()) {
    start_waiting(robot, route[0], std::move(way));
    resolve_from(robot);
  } else {
    r.waiting = false;
    r.blockers.clear();
    r.blocked_edge.reset();
    if (was_waiting) wake_waiting_on(robot);  // a robot that yielded to it may go now
  }
  if (released) wake_waiting_on(robot);
  notify();
  return held;
}

void Reservations::crossed(RobotId robot, map::EdgeIndex edge) {
  Robot& r = robots_.at(robot);
  if (!r.granted.empty() && r.granted.front() == edge) {
    release_node(robot, r.at);
    release_passage(robot, edge);
    r.granted.erase(r.granted.begin());
  } else {  // moved without a grant: it is where it is, and holds nothing ahead
    release_ahead(robot, 0);
    release_node(robot, r.at);
    hold_node(robot, map_.to_index(edge));
  }
  r.at = map_.to_index(edge);
  wake_waiting_on(robot);
  notify();
}

void Reservations::stop(RobotId robot, map::NodeIndex here) {
  Robot& r = robots_.at(robot);
  release_ahead(robot, 0);
  if (here != r.at) {
    release_node(robot, r.at);
    r.at = here;
    hold_node(robot, here);
  }
  r.waiting = false;
  r.blockers.clear();
  r.blocked_edge.reset();
  r.wanted.clear();
  // yield_to stays: a robot that has driven aside and stopped there still lets the robots it made
  // way for go first (else it would take the freed way back before their call to ask again).
  wake_waiting_on(robot);
  notify();
}

void Reservations::start_waiting(RobotId robot, map::EdgeIndex edge, std::vector<RobotId> blockers) {
  Robot& r = robots_[robot];
  if (!r.waiting) r.wait_order = ++wait_counter_;
  r.waiting = true;
  r.blockers = std::move(blockers);
  r.blocked_edge = edge;
}

void Reservations::wake_waiting_on(RobotId released_by) {
  std::vector<RobotId> woken;
  for (RobotId w = 0; w < robots_.size(); ++w)
    if (w != released_by && robots_[w].present && robots_[w].waiting && contains(robots_[w].blockers, released_by))
      woken.push_back(w);
  std::sort(woken.begin(), woken.end(),
            [&](RobotId a, RobotId b) { return robots_[a].wait_order < robots_[b].wait_order; });
  for (RobotId w : woken) {
    const bool queued =
        std::any_of(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.robot == w && !p.make_way; });
    if (!queued) pending_.push_back({w, std::nullopt});
  }
}

void Reservations::refresh_blockers(RobotId robot) {
  Robot& r = robots_[robot];
  if (!r.waiting || r.wanted.empty()) return;
  r.blockers = unit_in_the_way(robot, std::span(r.wanted).first(unit_length(r.wanted, 0)));
  if (r.blockers.empty() &&
      std::none_of(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.robot == robot && !p.make_way; }))
    pending_.push_back({robot, std::nullopt});  // its way is clear now: it asks again
}

void Reservations::resolve_from(RobotId start) {
  // The robots the wait leads to, each waiting one for what stands in its way now.
  std::vector<bool> seen(robots_.size(), false);
  std::vector<RobotId> reached{start};
  seen[start] = true;
  for (std::size_t i = 0; i < reached.size(); ++i) {
    refresh_blockers(reached[i]);
    for (RobotId b : robots_[reached[i]].blockers)
      if (!seen[b] && robots_[b].present && robots_[reached[i]].waiting) {
        seen[b] = true;
        reached.push_back(b);
      }
  }
  // Stuck: waiting for stuck robots only, or parked. A robot moving or at work ends its hold itself.
  std::vector<bool> stuck(robots_.size(), false);
  for (RobotId x : reached) {
    const Robot& r = robots_[x];
    stuck[x] = (r.waiting && !r.blockers.empty()) || (r.parked && r.granted.empty());
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (RobotId x : reached) {
      if (!stuck[x] || !robots_[x].waiting) continue;
      if (std::any_of(robots_[x].blockers.begin(), robots_[x].blockers.end(), [&](RobotId b) { return !stuck[b]; })) {
        stuck[x] = false;
        changed = true;
      }
    }
  }
  if (!stuck[start]) return;
  // What every waiting robot needs (not only these: a robot sent aside for one must not land in
  // another's way): kept clear by whoever is sent aside.
  const auto keep_clear_for = [&](RobotId moving) {
    std::vector<bool> keep(map_.node_count(), false);
    for (RobotId x = 0; x < robots_.size(); ++x) {
      if (x == moving || !robots_[x].present || !robots_[x].waiting) continue;
      keep[robots_[x].at] = true;
      for (map::EdgeIndex e : robots_[x].wanted) keep[map_.to_index(e)] = true;
    }
    return keep;
  };
  const auto waiting_for = [&](RobotId blocker) {
    std::vector<RobotId> who;
    for (RobotId x : reached)
      if (stuck[x] && robots_[x].waiting && contains(robots_[x].blockers, blocker)) who.push_back(x);
    return who;
  };
  // Ways through doors last: a door may be shut, and a robot sent into it comes back to where it was.
  for (const bool doors : {false, true})
    for (RobotId x : reached)
      if (stuck[x] && !robots_[x].waiting &&
          send_aside(x, MakeWay::Why::kParked, waiting_for(x), keep_clear_for(x), doors))
        return;
  // A deadlock: the stuck robots wait for each other. The lowest rank moves (the latest to join
  // among equals).
  std::vector<RobotId> order;
  for (RobotId x : reached)
    if (stuck[x] && robots_[x].waiting) order.push_back(x);
  // One robot waiting for parked robots that cannot move: sending it aside frees nobody.
  if (order.size() < 2) {
    ++unresolved_;
    return;
  }
  std::sort(order.begin(), order.end(), [&](RobotId a, RobotId b) {
    if (robots_[a].rank != robots_[b].rank) return robots_[a].rank < robots_[b].rank;
    return a > b;
  });
  for (const bool doors : {false, true})
    for (RobotId x : order) {
      std::vector<RobotId> others;
      for (RobotId y : order)
        if (y != x) others.push_back(y);
      if (send_aside(x, MakeWay::Why::kDeadlock, std::move(others), keep_clear_for(x), doors)) return;
    }
  ++unresolved_;
}

std::optional<std::vector<map::EdgeIndex>> Reservations::way_aside(RobotId robot, const std::vector<bool>& keep_clear,
                                                                   bool through_doors) const {
  const map::NodeIndex from = robots_[robot].at;
  std::vector<std::optional<map::EdgeIndex>> came_by(map_.node_count());
  std::vector<bool> seen(map_.node_count(), false);
  std::deque<map::NodeIndex> queue{from};
  seen[from] = true;
  while (!queue.empty()) {
    const map::NodeIndex n = queue.front();
    queue.pop_front();
    if (n != from && !keep_clear[n]) {
      std::vector<map::EdgeIndex> route;
      for (map::NodeIndex at = n; at != from; at = map_.from_index(*came_by[at])) route.push_back(*came_by[at]);
      std::reverse(route.begin(), route.end());
      return route;
    }
    for (map::EdgeIndex e : map_.out_edges(n)) {
      const map::NodeIndex to = map_.to_index(e);
      if (seen[to] || (!through_doors && map_.edge(e).door) || !in_the_way(robot, e).empty()) continue;
      seen[to] = true;
      came_by[to] = e;
      queue.push_back(to);
    }
  }
  return std::nullopt;
}

bool Reservations::send_aside(RobotId robot, MakeWay::Why why, std::vector<RobotId> for_robots,
                              const std::vector<bool>& keep_clear, bool through_doors) {
  std::optional<std::vector<map::EdgeIndex>> route = way_aside(robot, keep_clear, through_doors);
  if (!route) return false;
  Robot& r = robots_[robot];
  release_ahead(robot, 0);
  for (map::EdgeIndex e : *route) grant(robot, e);
  r.waiting = false;  // its blockers stay: what it waited for, for the record
  r.parked = false;
  r.wanted = *route;
  r.yield_to = for_robots;
  resolutions_.push_back({.why = why, .robot = robot, .to = map_.to_index(route->back()), .for_robots = for_robots});
  std::erase_if(pending_, [&](const Pending& p) { return p.robot == robot && !p.make_way; });
  pending_.push_back({robot, MakeWay{.why = why, .route = std::move(*route), .for_robots = std::move(for_robots)}});
  return true;
}

void Reservations::notify() {
  if (notifying_) return;
  notifying_ = true;
  while (!pending_.empty()) {
    const Pending p = std::move(pending_.front());
    pending_.erase(pending_.begin());
    ReservationListener* l = robots_[p.robot].listener;
    if (!l || !robots_[p.robot].present) continue;
    if (p.make_way) {
      l->on_make_way(*p.make_way);
    } else if (robots_[p.robot].waiting) {
      l->on_way_may_be_clear();
    }
  }
  notifying_ = false;
}

}  // namespace rondo::traffic
