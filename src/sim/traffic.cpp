#include "rondo/sim/traffic.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace rondo::sim {

const char* to_string(HoldUp::End end) {
  switch (end) {
    case HoldUp::End::kWaiting:
      return "waiting";
    case HoldUp::End::kPassed:
      return "passed";
    case HoldUp::End::kTimedOut:
      return "timed out";
    case HoldUp::End::kStopped:
      return "stopped";
  }
  return "waiting";
}

Traffic::Traffic(const map::TopoMap& map, TrafficOptions options)
    : map_(map),
      options_(options),
      standing_(map.node_count(), 0),
      inbound_(map.node_count(), 0),
      on_edge_(map.edge_count(), 0) {
  capacity_.reserve(map.node_count());
  for (const map::Node& n : map.nodes()) capacity_.push_back(n.capacity);
  passage_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) passage_.push_back(map::passage_narrow(map, e));
}

void Traffic::set_capacity(map::NodeIndex node, int capacity) {
  if (capacity < 1) throw std::logic_error("Traffic::set_capacity: a node holds one robot at least");
  capacity_.at(node) = capacity;
}

TrafficPosition Traffic::position(RobotId robot) const {
  const Robot& r = robots_.at(robot);
  return {.node = r.node, .edge = r.edge, .held = r.hold.has_value()};
}

Traffic::RobotId Traffic::join(std::string name, map::NodeIndex at, Time now, TrafficListener* listener) {
  if (at >= map_.node_count()) throw std::logic_error("Traffic::join: not a node of the map");
  robots_.push_back({.name = std::move(name), .listener = listener, .node = at});
  stand(robots_.size() - 1, at, now);
  changed();
  return robots_.size() - 1;
}

void Traffic::leave(RobotId robot, Time now) {
  Robot& r = robots_.at(robot);
  if (!r.present) return;
  if (r.hold) end_hold(robot, now, HoldUp::End::kStopped);
  r.present = false;
  r.listener = nullptr;
  if (r.edge) {
    --on_edge_[*r.edge];
    --inbound_[map_.to_index(*r.edge)];
    wake(map_.to_index(*r.edge), *r.edge);
  } else {
    --standing_[r.node];
    wake(r.node, std::nullopt);
  }
  changed();
}

std::optional<Traffic::RobotId> Traffic::first_standing(map::NodeIndex node, std::optional<RobotId> besides) const {
  for (RobotId i = 0; i < robots_.size(); ++i)
    if (robots_[i].present && !robots_[i].edge && robots_[i].node == node && i != besides) return i;
  return std::nullopt;
}

bool Traffic::same_passage(map::EdgeIndex a, map::EdgeIndex b) const {
  const map::NodeIndex a1 = map_.from_index(a), a2 = map_.to_index(a);
  const map::NodeIndex b1 = map_.from_index(b), b2 = map_.to_index(b);
  return (a1 == b1 && a2 == b2) || (a1 == b2 && a2 == b1);
}

std::vector<Traffic::RobotId> Traffic::in_passage(map::EdgeIndex edge, bool against_only) const {
  std::vector<RobotId> out;
  for (RobotId i = 0; i < robots_.size(); ++i) {
    const Robot& r = robots_[i];
    if (!r.present || !r.edge || !same_passage(*r.edge, edge)) continue;
    if (against_only && map_.from_index(*r.edge) == map_.from_index(edge)) continue;
    out.push_back(i);
  }
  return out;
}

std::optional<Blocker> Traffic::blocker(RobotId robot, map::EdgeIndex edge) const {
  const map::NodeIndex far = map_.to_index(edge);
  if (standing_[far] + inbound_[far] >= capacity_[far]) {
    const std::string& node = map_.node(far).name;
    if (const auto there = first_standing(far, robot)) return Blocker{robots_[*there].name, "at " + node};
    for (const Robot& r : robots_)
      if (r.present && r.edge && map_.to_index(*r.edge) == far) return Blocker{r.name, "on its way to " + node};
  }
  const map::Narrow mark = passage_[edge];
  if (mark == map::Narrow::kNone) return std::nullopt;
  const std::vector<RobotId> in = in_passage(edge, mark == map::Narrow::kOneWay);
  if (in.empty()) return std::nullopt;
  const Robot& first = robots_[in.front()];
  return Blocker{first.name, fmt::format("on {} (narrow: {})", map_.edge(*first.edge).id, map::to_string(mark))};
}

void Traffic::hold(RobotId robot, map::EdgeIndex edge, Time now) {
  Robot& r = robots_.at(robot);
  if (r.hold || r.edge) throw std::logic_error("Traffic::hold: the robot is waiting or moving already");
  HoldUp h{.robot = r.name, .edge = edge, .node = map_.node(r.node).name, .start = now, .end = now};
  if (auto b = blocker(robot, edge)) h.blocker = std::move(*b);
  r.hold = hold_ups_.size();
  hold_ups_.push_back(std::move(h));
  waiting_.push_back(robot);
  changed();
}

void Traffic::end_hold(RobotId robot, Time now, HoldUp::End how) {
  Robot& r = robots_.at(robot);
  if (!r.hold) return;
  HoldUp& h = hold_ups_[*r.hold];
  h.end = now;
  h.how = how;
  r.hold.reset();
  waiting_.erase(std::find(waiting_.begin(), waiting_.end(), robot));
  changed();
}

void Traffic::enter(RobotId robot, map::EdgeIndex edge, Time now) {
  Robot& r = robots_.at(robot);
  if (r.edge || r.hold || map_.from_index(edge) != r.node)
    throw std::logic_error("Traffic::enter: the robot is not standing at the edge's start");
  --standing_[r.node];
  ++on_edge_[edge];
  ++inbound_[map_.to_index(edge)];
  r.edge = edge;
  count_passage_collision(robot, edge, now);
  wake(r.node, std::nullopt);
  changed();
}

void Traffic::count_passage_collision(RobotId robot, map::EdgeIndex edge, Time now) {
  const map::Narrow mark = passage_[edge];
  if (mark == map::Narrow::kNone) return;
  std::vector<RobotId> others = in_passage(edge, mark == map::Narrow::kOneWay);
  std::erase(others, robot);
  if (others.empty()) return;
  Collision c{
      .kind = Collision::Kind::kPassage, .at = now, .place = map_.edge(edge).id, .robots = {robots_[robot].name}};
  for (RobotId o : others) c.robots.push_back(robots_[o].name);
  collisions_.push_back(std::move(c));
}

void Traffic::arrive(RobotId robot, map::NodeIndex node, Time now) {
  Robot& r = robots_.at(robot);
  if (!r.edge || (node != map_.from_index(*r.edge) && node != map_.to_index(*r.edge)))
    throw std::logic_error("Traffic::arrive: the robot is not on an edge that ends there");
  const map::EdgeIndex edge = *r.edge;
  --on_edge_[edge];
  --inbound_[map_.to_index(edge)];
  r.edge.reset();
  r.node = node;
  stand(robot, node, now);
  // Its passage is free of it; back at its start, its claim on the far node is given up.
  std::optional<map::NodeIndex> unclaimed;
  if (node != map_.to_index(edge)) unclaimed = map_.to_index(edge);
  wake(unclaimed, edge);
  changed();
}

void Traffic::carry(RobotId robot, map::NodeIndex node, Time now) {
  Robot& r = robots_.at(robot);
  if (r.edge || r.hold) throw std::logic_error("Traffic::carry: the robot is not standing");
  if (node == r.node) return;
  const map::NodeIndex from = r.node;
  --standing_[from];
  r.node = node;
  stand(robot, node, now);
  wake(from, std::nullopt);
  changed();
}

void Traffic::stand(RobotId robot, map::NodeIndex node, Time now) {
  if (++standing_[node] <= capacity_[node]) return;
  Collision c{
      .kind = Collision::Kind::kNode, .at = now, .place = map_.node(node).name, .robots = {robots_[robot].name}};
  for (RobotId i = 0; i < robots_.size(); ++i)
    if (i != robot && robots_[i].present && !robots_[i].edge && robots_[i].node == node)
      c.robots.push_back(robots_[i].name);
  collisions_.push_back(std::move(c));
}

void Traffic::wake(std::optional<map::NodeIndex> freed_node, std::optional<map::EdgeIndex> freed_passage) {
  // A copy: a listener may end its hold at once (it should only post a look, but need not).
  const std::vector<RobotId> waiting = waiting_;
  for (RobotId w : waiting) {
    const Robot& r = robots_[w];
    if (!r.hold || r.listener == nullptr) continue;
    const map::EdgeIndex wanted = hold_ups_[*r.hold].edge;
    const bool node = freed_node && map_.to_index(wanted) == *freed_node;
    const bool passage =
        freed_passage && passage_[wanted] != map::Narrow::kNone && same_passage(wanted, *freed_passage);
    if (node || passage) r.listener->on_way_may_be_clear();
  }
}

void Traffic::changed() const {
  if (observer_) observer_();
}

}  // namespace rondo::sim
