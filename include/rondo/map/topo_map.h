// The topological map: places the robot can stand at (nodes, with a pose) and the directed edges
// between them, each naming the motion behaviour that crosses it. Every other module plans and
// learns over this graph.
//
//   std::vector<Node> nodes = {{.name = "Kitchen", .pose = {0, 0, 0}},
//                              {.name = "Office", .pose = {4, 3, 1.57}}};
//   std::vector<Edge> edges = {{.id = "Kitchen_Office", .from = "Kitchen", .to = "Office",
//                               .action = "move_base", .top_speed = 0.55}};
//   Result<TopoMap> map = TopoMap::build("flat", std::move(nodes), std::move(edges));
//   if (!map) return map.error();            // "edges[0] 'Kitchen_Office': ..." on bad input
//   NodeIndex kitchen = *map->find_node("Kitchen");
//   for (EdgeIndex e : map->out_edges(kitchen)) use(map->edge(e).to);
//
// A TopoMap is a value: immutable once built, cheap to share by const reference, and compared
// with == (same name, same nodes and edges in the same order). Units are SI: metres, radians,
// metres per second.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::map {

// Dense indices into TopoMap::nodes() and TopoMap::edges(), stable for the life of the map.
using NodeIndex = std::size_t;
using EdgeIndex = std::size_t;

// The STRANDS defaults, used when a map does not give a node's goal tolerances.
inline constexpr double kDefaultXyGoalTolerance = 0.3;   // metres
inline constexpr double kDefaultYawGoalTolerance = 0.1;  // radians
// The motion action of an edge that does not name one.
inline constexpr std::string_view kDefaultAction = "move_base";
// The most robots a node may say it holds at once (`capacity`).
inline constexpr int kMaxNodeCapacity = 1000;

// How robots share an edge's passage (docs/map-format.md, "Traffic"): kNone, they pass each other
// freely; kSingle, one robot at a time, in either direction; kOneWay, several may follow each
// other, in one direction at a time.
enum class Narrow { kNone, kSingle, kOneWay };

// "none", "single", "one_way": the words of the map format.
const char* to_string(Narrow narrow);
// The mark a map file writes ("single", "one_way"); nothing for any other word.
std::optional<Narrow> narrow_from_string(std::string_view word);

// A position and heading in the map frame.
struct Pose {
  double x = 0;    // metres
  double y = 0;    // metres
  double yaw = 0;  // radians, counter-clockwise from the x axis, in (-pi, pi] when imported
  bool operator==(const Pose&) const = default;
};

// A vertex of a node's influence polygon, relative to the node's position (not rotated by yaw).
struct Point2 {
  double x = 0;  // metres
  double y = 0;  // metres
  bool operator==(const Point2&) const = default;
};

struct Node {
  std::string name{};  // unique in the map, non-empty, no control characters
  Pose pose{};
  double xy_goal_tolerance = kDefaultXyGoalTolerance;    // metres, >= 0
  double yaw_goal_tolerance = kDefaultYawGoalTolerance;  // radians, >= 0
  // The area in which the robot counts as being at this node; empty when the map has none.
  std::vector<Point2> influence{};
  // Free-form facts about the place (e.g. STRANDS `contains` rooms, a `description`): a JSON
  // object, or null when there are none. rondo does not interpret it; it is kept and written back.
  Json meta{};
  // How many robots the place holds at once (an atrium, a bay with two docks: more than 1).
  int capacity = 1;
  bool operator==(const Node&) const = default;
};

struct Edge {
  std::string id{};                   // unique in the map; "<from>_<to>" by convention
  std::string from{};                 // name of the node the edge leaves
  std::string to{};                   // name of the node it reaches; never equal to `from`
  std::string action{};               // the motion behaviour: move_base, human_aware_navigation, doorPassing...
  std::optional<double> top_speed{};  // m/s, > 0; the robot's speed limit on this edge
  // The door this edge passes through; both directions through one door share the id, so door
  // models and observations can attach to it. Absent for edges without a door.
  std::optional<std::string> door{};
  // Whether robots must take turns on it: the passage between its two nodes, both directions.
  Narrow narrow = Narrow::kNone;
  bool operator==(const Edge&) const = default;
};

class TopoMap {
 public:
  // An empty map with no name.
  TopoMap() = default;

  // Checks every rule of map_validation.h (unique names and ids, edges between known distinct
  // nodes, finite poses, positive speeds...) and builds the lookup tables. The error names the
  // first problem and how many more there are; a loader that knows where each node and edge came
  // from should call find_map_problems() first to name the file and line.
  static Result<TopoMap> build(std::string name, std::vector<Node> nodes, std::vector<Edge> edges);

  // The map's name (e.g. the STRANDS pointset); may be empty.
  const std::string& name() const { return name_; }
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<Edge>& edges() const { return edges_; }
  std::size_t node_count() const { return nodes_.size(); }
  std::size_t edge_count() const { return edges_.size(); }

  // Precondition: the index is below node_count() / edge_count().
  const Node& node(NodeIndex i) const { return nodes_.at(i); }
  const Edge& edge(EdgeIndex i) const { return edges_.at(i); }
  NodeIndex from_index(EdgeIndex e) const { return edge_ends_.at(e).first; }
  NodeIndex to_index(EdgeIndex e) const { return edge_ends_.at(e).second; }

  std::optional<NodeIndex> find_node(std::string_view name) const;
  std::optional<EdgeIndex> find_edge(std::string_view id) const;

  // The edges leaving / entering node `i`, in the order of edges().
  std::span<const EdgeIndex> out_edges(NodeIndex i) const;
  std::span<const EdgeIndex> in_edges(NodeIndex i) const;

  // Same name, same nodes and same edges in the same order (the lookup tables follow from them).
  bool operator==(const TopoMap& other) const;

 private:
  struct StringHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  using Index = std::unordered_map<std::string, std::size_t, StringHash, std::equal_to<>>;

  std::string name_;
  std::vector<Node> nodes_;
  std::vector<Edge> edges_;
  Index node_index_;
  Index edge_index_;
  std::vector<std::pair<NodeIndex, NodeIndex>> edge_ends_;
  // Adjacency in compressed form: the out-edges of node i are out_[out_start_[i] .. out_start_[i+1]).
  std::vector<std::size_t> out_start_;
  std::vector<EdgeIndex> out_;
  std::vector<std::size_t> in_start_;
  std::vector<EdgeIndex> in_;
};

// The mark of the passage edge `e` belongs to: the strictest (single, then one_way) of every edge
// between its two nodes, in either direction, so that marking one direction marks the passage.
Narrow passage_narrow(const TopoMap& map, EdgeIndex e);

}  // namespace rondo::map
