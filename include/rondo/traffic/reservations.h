// The traffic manager's reservations (docs/traffic.md): which robot holds which nodes and narrow
// passages of the building, granted ahead of each robot along the route it asks for, released as
// it leaves them; who waits for whom; and what breaks a wait that nobody's moving would end.
//
//   Reservations r(map, {.lookahead = 2});
//   RobotId a = r.join("r1", dock_1, &listener_1);     // holds its node
//   std::size_t n = r.request(a, here, route);          // the first n edges of route are held: drive them
//   r.crossed(a, route[0]);                             // at its far node: the node left is free again
//   r.stop(a, here);                                    // stopped (failed, cancelled, arrived): all ahead freed
//
// The rules (the prevention rule and its proof are in docs/traffic.md):
// - A robot always holds the node it stands at. It is granted an edge only with the edge's far
//   node (a node holds `capacity` robots), and, for a narrow edge, with its passage (single: one
//   robot; one_way: robots in one direction).
// - A run of narrow edges on a route is granted whole, with the node after it, or not at all: a
//   robot never waits inside a narrow section.
// - The way into a dead end (a room, a counter, a dock: one neighbour only) is granted together
//   with the node in front of it: a robot never waits in front of a dead end, where it would shut
//   in the robot inside.
// - Grants go `lookahead` edges ahead (a narrow section may take them further), no further.
// - A robot granted nothing waits. Whenever a robot starts waiting, the robots it waits for are
//   followed: a parked robot (set_parked) in the way is asked to make way; a set of robots each
//   waiting for another of the set (a deadlock) is broken by sending the one of lowest rank to the
//   nearest node that no waiting robot needs. Both are sent a route already granted; a way without
//   doors is preferred (for a robot of higher rank too), since a door may be shut. A robot sent
//   aside is granted nothing more while a robot it made way for still waits (else it would take the
//   freed way back before them, and the deadlock would form again, and again).
// Listeners are called after the call that caused them has finished its changes, and may call
// back in. Only one thread.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rondo/map/topo_map.h"

namespace rondo::traffic {

using RobotId = std::size_t;

struct ReservationOptions {
  // Edges granted ahead of a robot: the edge it drives next, and one more, so that a robot whose
  // way is clear is never stopped at the end of what it holds.
  std::size_t lookahead = 2;
  bool operator==(const ReservationOptions&) const = default;
};

// Why a robot is sent aside.
struct MakeWay {
  enum class Why { kDeadlock, kParked };
  Why why = Why::kDeadlock;
  std::vector<map::EdgeIndex> route;  // granted: from where it stands to the node it is sent to
  std::vector<RobotId> for_robots;    // the robots it makes way for (a deadlock: the others in it)
};
const char* to_string(MakeWay::Why why);  // "deadlock", "parked"

class ReservationListener {
 public:
  virtual ~ReservationListener() = default;
  // Something it waits for was released: request again.
  virtual void on_way_may_be_clear() = 0;
  // Drive `make_way.route` (held already), then go on with its own work.
  virtual void on_make_way(const MakeWay& make_way) = 0;
};

// One resolution, for the record: who was sent where, and for whom.
struct Resolution {
  MakeWay::Why why = MakeWay::Why::kDeadlock;
  RobotId robot = 0;
  map::NodeIndex to = 0;
  std::vector<RobotId> for_robots{};
};

class Reservations {
 public:
  explicit Reservations(const map::TopoMap& map, ReservationOptions options = {});
  Reservations(const Reservations&) = delete;
  Reservations& operator=(const Reservations&) = delete;

  const map::TopoMap& map() const { return map_; }
  const ReservationOptions& options() const { return options_; }
  void set_capacity(map::NodeIndex node, int capacity);
  int capacity(map::NodeIndex node) const { return capacity_.at(node); }

  // A robot standing at `at` (held even beyond the node's capacity: it is there). `listener` may be
  // null, and must outlive leave().
  RobotId join(std::string name, map::NodeIndex at, ReservationListener* listener);
  void leave(RobotId robot);
  // Higher ranks are kept moving in a deadlock (e.g. the running task's priority).
  void set_rank(RobotId robot, int rank);
  // A parked robot stands idle and is asked to make way for a robot that waits for it.
  void set_parked(RobotId robot, bool parked);

  // The robot stands at `here` (its node, re-read: a robot carried elsewhere holds its new node)
  // and asks for `route`, consecutive edges from `here`. Grants what it can (keeping what it held
  // of the same route) and releases what it held off it; returns how many of route's first edges
  // it now holds. 0 for a non-empty route: it waits until a listener call (which may come at once,
  // before this returns: a deadlock its wait closed may send it aside).
  std::size_t request(RobotId robot, map::NodeIndex here, std::span<const map::EdgeIndex> route);
  // The robot crossed `edge`, the first it held: it stands at the far node, the node left is freed.
  void crossed(RobotId robot, map::EdgeIndex edge);
  // The robot stopped at `here` (arrived, failed, cancelled, halted): it holds `here` only.
  void stop(RobotId robot, map::NodeIndex here);

  // Read-outs.
  std::size_t robot_count() const { return robots_.size(); }
  const std::string& name(RobotId robot) const { return robots_.at(robot).name; }
  bool present(RobotId robot) const { return robots_.at(robot).present; }
  map::NodeIndex at(RobotId robot) const { return robots_.at(robot).at; }
  const std::vector<map::EdgeIndex>& granted(RobotId robot) const { return robots_.at(robot).granted; }
  bool waiting(RobotId robot) const { return robots_.at(robot).waiting; }
  // Whom a waiting robot waits for: the holders of the first node or passage it could not have
  // (kept after it was sent aside: what it waited for).
  const std::vector<RobotId>& waits_for(RobotId robot) const { return robots_.at(robot).blockers; }
  // Where the waiting robot waits to go: the edge it could not have.
  std::optional<map::EdgeIndex> waits_at(RobotId robot) const { return robots_.at(robot).blocked_edge; }
  // The robots holding a node (standing there, or granted it).
  const std::vector<RobotId>& holders(map::NodeIndex node) const { return node_holders_.at(node); }
  // The robots holding an edge's narrow passage (empty for an edge that is not narrow).
  std::vector<RobotId> passage_holders(map::EdgeIndex edge) const;
  const std::vector<Resolution>& resolutions() const { return resolutions_; }
  // Deadlocks found that no robot could be sent aside from (yet): they are tried again at the next
  // change.
  std::size_t unresolved() const { return unresolved_; }

 private:
  struct Robot {
    std::string name;
    ReservationListener* listener = nullptr;
    bool present = true;
    int rank = 0;
    bool parked = false;
    map::NodeIndex at = 0;
    std::vector<map::EdgeIndex> granted{};  // held, in order, the first leaving `at`
    std::vector<map::EdgeIndex> wanted{};   // the last route asked for
    bool waiting = false;
    std::vector<RobotId> blockers{};
    std::optional<map::EdgeIndex> blocked_edge{};
    std::size_t wait_order = 0;  // when it began to wait (a counter)
    std::vector<RobotId> yield_to{};  // sent aside for these: they go first while they wait
  };
  struct PassageHold {
    RobotId robot;
    bool forward;  // direction: from the lower node index to the higher
  };

  // Whether `robot` may be granted `edge` now (besides what it holds); who stands in the way.
  std::vector<RobotId> in_the_way(RobotId robot, map::EdgeIndex edge) const;
  // Who stands in the way of any edge of one grant (unit_length edges).
  std::vector<RobotId> unit_in_the_way(RobotId robot, std::span<const map::EdgeIndex> unit) const;
  // How many edges from route[i] form one grant: a narrow section whole; the edge to the node in
  // front of a dead end with the edge into it; else one edge.
  std::size_t unit_length(std::span<const map::EdgeIndex> route, std::size_t i) const;
  void grant(RobotId robot, map::EdgeIndex edge);
  void release_ahead(RobotId robot, std::size_t keep);
  void release_node(RobotId robot, map::NodeIndex node);
  void release_passage(RobotId robot, map::EdgeIndex edge);
  void hold_node(RobotId robot, map::NodeIndex node);
  std::size_t passage(map::EdgeIndex edge) const { return passage_of_.at(edge); }
  bool forward(map::EdgeIndex edge) const { return map_.from_index(edge) < map_.to_index(edge); }
  void start_waiting(RobotId robot, map::EdgeIndex edge, std::vector<RobotId> blockers);
  void wake_waiting_on(RobotId released_by);
  // What stands in a waiting robot's way now; nothing: it is told to ask again.
  void refresh_blockers(RobotId robot);
  // Follows the waits from `robot`: asks a parked robot to make way, or breaks a deadlock.
  void resolve_from(RobotId robot);
  // The way from where `robot` stands to the nearest node it can have that is not in `keep_clear`,
  // over edges it can have (through doors or not); nothing when there is none.
  std::optional<std::vector<map::EdgeIndex>> way_aside(RobotId robot, const std::vector<bool>& keep_clear,
                                                       bool through_doors) const;
  bool send_aside(RobotId robot, MakeWay::Why why, std::vector<RobotId> for_robots, const std::vector<bool>& keep_clear,
                  bool through_doors);
  void notify();

  const map::TopoMap& map_;
  ReservationOptions options_;
  std::vector<int> capacity_;
  std::vector<std::size_t> passage_of_;                  // per edge: its passage, or kNoPassage
  std::vector<map::Narrow> passage_mark_;                // per passage
  std::vector<bool> dead_end_;                           // per node: one neighbour only
  std::vector<std::vector<RobotId>> node_holders_;       // per node
  std::vector<std::vector<PassageHold>> passage_holds_;  // per passage
  std::vector<Robot> robots_;
  std::vector<Resolution> resolutions_;
  std::size_t unresolved_ = 0;
  std::size_t wait_counter_ = 0;
  // Listener calls waiting for the end of the call that caused them.
  struct Pending {
    RobotId robot;
    std::optional<MakeWay> make_way;  // nothing: the way may be clear
  };
  std::vector<Pending> pending_;
  bool notifying_ = false;
};

}  // namespace rondo::traffic
