// The robots of one simulated building in each other's way (docs/simulation.md, "Traffic"): where
// each robot is (standing at a node, or on an edge towards its far node), whether it may enter an
// edge now, and every meeting: hold-ups and collisions. One Traffic is shared by every SimRobot of
// the building; a robot alone needs none.
//
//   Traffic traffic(map, world.traffic);                  // capacities and narrow marks of the map
//   SimRobot r1(clock, map, world, {.start = a, .name = "r1", .traffic = &traffic});
//   SimRobot r2(clock, map, world, {.start = b, .name = "r2", .traffic = &traffic});
//   clock.run_until(end);
//   for (const HoldUp& h : traffic.hold_ups()) ...;       // "r2 held by r1 at Hall for 40s"
//   traffic.collisions().size();                          // counted, never prevented
//
// The rules (the robot asks before each edge, SimRobot does the waiting):
// - A node holds `capacity` robots (the map's, raised by set_capacity()). A robot may not enter an
//   edge whose far node is full: robots standing there and robots on an edge towards it (each
//   will claim it) count.
// - A narrow passage (map::passage_narrow: the edges between two nodes) takes one robot at a time
//   (single), or robots in one direction at a time (one_way).
// - A robot that arrives at a node beyond its capacity (back from a failed attempt, carried to its
//   dock, placed there at the start) is a collision at the node; one that enters a narrow passage
//   against another is a collision on it. Both are counted, with the robots and the place.
// Deterministic: the same calls in the same order give the same record. Waiting robots hear of a
// change that may free their way (a node left, a passage left) in the order they began to wait.
// Only one thread: the clock's.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::sim {

struct TrafficOptions {
  // How long a robot waits for its way to clear before the attempt fails. A minute: longer than a
  // robot ahead takes to cross a corridor segment or a door (10-40 s in the example buildings), so
  // waiting behind one passes; shorter than the two minutes after which issue 42 calls a wait a
  // deadlock, so two robots waiting for each other give up, and their executors plan again.
  Duration hold_timeout = seconds(60);
  bool operator==(const TrafficOptions&) const = default;
};

// Tells a waiting robot that its way may have cleared; it looks again (later, on its clock).
class TrafficListener {
 public:
  virtual ~TrafficListener() = default;
  virtual void on_way_may_be_clear() = 0;
};

// Who keeps a robot out of an edge.
struct Blocker {
  std::string robot;  // the first blocking robot's name
  std::string place;  // "at WayPoint7", "on its way to WayPoint7", "on WayPoint3_WayPoint7 (narrow: single)"
  std::string text() const { return "held up by " + robot + " " + place; }
};

// One meeting: a robot held at its node, waiting to enter an edge.
struct HoldUp {
  enum class End { kWaiting, kPassed, kTimedOut, kStopped };  // stopped: cancelled, a fault, gone
  std::string robot{};
  map::EdgeIndex edge = 0;
  std::string node{};  // where it waits
  Blocker blocker{};   // who held it up when it began to wait
  Time start{};
  Time end{};  // when it ended (start while waiting)
  End how = End::kWaiting;
  Duration held() const { return end - start; }
};

const char* to_string(HoldUp::End end);  // "waiting", "passed", "timed out", "stopped"

struct Collision {
  enum class Kind { kNode, kPassage };  // beyond a node's capacity; against another in a narrow passage
  Kind kind = Kind::kNode;
  Time at{};
  std::string place{};                // the node's name, or the edge's id
  std::vector<std::string> robots{};  // the one that came, then the others there
};

// Where a robot is, for the traffic.
struct TrafficPosition {
  map::NodeIndex node = 0;               // standing here, or the edge's start when on one
  std::optional<map::EdgeIndex> edge{};  // on this edge, towards its far node
  bool held = false;                     // standing at `node`, waiting to enter an edge
};

class Traffic {
 public:
  using RobotId = std::size_t;

  // Capacities and narrow marks from `map`, which must outlive the traffic.
  explicit Traffic(const map::TopoMap& map, TrafficOptions options = {});
  Traffic(const Traffic&) = delete;
  Traffic& operator=(const Traffic&) = delete;

  const TrafficOptions& options() const { return options_; }
  const map::TopoMap& map() const { return map_; }
  // A node's room, e.g. a deployment's dock with room for more robots than the map says.
  void set_capacity(map::NodeIndex node, int capacity);
  int capacity(map::NodeIndex node) const { return capacity_.at(node); }

  // A robot standing at `at` from `now` (a collision if the node is full already). `listener` may
  // be null (the robot never waits) and must stay valid until leave().
  RobotId join(std::string name, map::NodeIndex at, Time now, TrafficListener* listener);
  // The robot is gone (its hold, if any, ends as stopped); its id stays unused.
  void leave(RobotId robot, Time now);

  // What keeps `robot`, standing at the edge's start, from entering `edge` now; nothing: go.
  std::optional<Blocker> blocker(RobotId robot, map::EdgeIndex edge) const;
  // The robot waits to enter `edge`, held up by blocker(); ends with end_hold().
  void hold(RobotId robot, map::EdgeIndex edge, Time now);
  void end_hold(RobotId robot, Time now, HoldUp::End how);
  // The robot leaves its node onto `edge` (asked blocker() first: else it is a collision).
  void enter(RobotId robot, map::EdgeIndex edge, Time now);
  // The robot leaves its edge and stands at `node`: the far node, or back at the start.
  void arrive(RobotId robot, map::NodeIndex node, Time now);
  // The robot, standing, is carried to `node` (people bringing an empty robot to its dock).
  void carry(RobotId robot, map::NodeIndex node, Time now);

  const std::vector<HoldUp>& hold_ups() const { return hold_ups_; }
  const std::vector<Collision>& collisions() const { return collisions_; }
  std::size_t robot_count() const { return robots_.size(); }
  const std::string& name(RobotId robot) const { return robots_.at(robot).name; }
  TrafficPosition position(RobotId robot) const;
  bool present(RobotId robot) const { return robots_.at(robot).present; }
  // The bookkeeping, for tests: robots standing at a node, on an edge towards it, on an edge.
  int standing(map::NodeIndex node) const { return standing_.at(node); }
  int inbound(map::NodeIndex node) const { return inbound_.at(node); }
  int on_edge(map::EdgeIndex edge) const { return on_edge_.at(edge); }
  // Called after every change of a robot's position or hold (tests check the bookkeeping there).
  void observe(std::function<void()> after_each_change) { observer_ = std::move(after_each_change); }

 private:
  struct Robot {
    std::string name;
    TrafficListener* listener = nullptr;
    map::NodeIndex node = 0;
    std::optional<map::EdgeIndex> edge{};
    std::optional<std::size_t> hold{};  // index into hold_ups_
    bool present = true;
  };

  void stand(RobotId robot, map::NodeIndex node, Time now);  // standing_ + the node's collision
  void count_passage_collision(RobotId robot, map::EdgeIndex edge, Time now);
  // The robots on the passage of `edge` (both directions), or only those going against it.
  std::vector<RobotId> in_passage(map::EdgeIndex edge, bool against_only) const;
  std::optional<RobotId> first_standing(map::NodeIndex node, std::optional<RobotId> besides) const;
  void wake(std::optional<map::NodeIndex> freed_node, std::optional<map::EdgeIndex> freed_passage);
  bool same_passage(map::EdgeIndex a, map::EdgeIndex b) const;
  void changed() const;

  const map::TopoMap& map_;
  TrafficOptions options_;
  std::vector<int> capacity_;
  std::vector<map::Narrow> passage_;  // per edge: its passage's mark
  std::vector<int> standing_;
  std::vector<int> inbound_;
  std::vector<int> on_edge_;
  std::vector<Robot> robots_;
  std::vector<RobotId> waiting_;  // held robots, in the order they began to wait
  std::vector<HoldUp> hold_ups_;
  std::vector<Collision> collisions_;
  std::function<void()> observer_;
};

}  // namespace rondo::sim
