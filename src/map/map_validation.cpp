#include "rondo/map/map_validation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "map_locate.h"
#include "rondo/core/utf8.h"

namespace rondo::map {
namespace {

// Why a name or id cannot be used, or nothing when it can.
std::optional<std::string> name_problem(const std::string& name, std::string_view what) {
  if (name.empty()) return fmt::format("{} must not be empty", what);
  if (first_invalid_utf8(name)) return fmt::format("{} must be UTF-8 text", what);
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return fmt::format("{} must not contain control characters", what);
  }
  return std::nullopt;
}

void check_node(const std::vector<Node>& nodes, std::size_t i, std::unordered_map<std::string_view, std::size_t>& seen,
                std::vector<MapProblem>& out) {
  const Node& n = nodes[i];
  auto add = [&](std::string field, std::string message) {
    out.push_back({MapProblem::Subject::kNode, i, std::move(field), std::move(message)});
  };
  if (auto p = name_problem(n.name, "a node name")) {
    add("name", *p);
  } else if (auto [it, fresh] = seen.emplace(n.name, i); !fresh) {
    add("name", fmt::format("node {} is already defined by nodes[{}]", quoted_name(n.name), it->second));
  }
  if (!std::isfinite(n.pose.x)) add("pose.x", "must be a finite number");
  if (!std::isfinite(n.pose.y)) add("pose.y", "must be a finite number");
  if (!std::isfinite(n.pose.yaw)) add("pose.yaw", "must be a finite number");
  if (!std::isfinite(n.xy_goal_tolerance) || n.xy_goal_tolerance < 0) {
    add("xy_goal_tolerance", "must be a finite number of metres, 0 or more");
  }
  if (!std::isfinite(n.yaw_goal_tolerance) || n.yaw_goal_tolerance < 0) {
    add("yaw_goal_tolerance", "must be a finite number of radians, 0 or more");
  }
  for (std::size_t v = 0; v < n.influence.size(); ++v) {
    if (!std::isfinite(n.influence[v].x) || !std::isfinite(n.influence[v].y)) {
      add(fmt::format("influence[{}]", v), "vertex coordinates must be finite numbers");
    }
  }
  if (!n.meta.is_null() && !n.meta.is_object()) add("meta", "must be a mapping");
  if (n.capacity < 1 || n.capacity > kMaxNodeCapacity) {
    add("capacity", fmt::format("must be a whole number of robots from 1 to {}, not {}", kMaxNodeCapacity, n.capacity));
  }
}

void check_edge(const std::vector<Edge>& edges, std::size_t i,
                const std::unordered_map<std::string_view, std::size_t>& nodes,
                std::unordered_map<std::string_view, std::size_t>& seen, std::vector<MapProblem>& out) {
  const Edge& e = edges[i];
  auto add = [&](std::string field, std::string message) {
    out.push_back({MapProblem::Subject::kEdge, i, std::move(field), std::move(message)});
  };
  if (auto p = name_problem(e.id, "an edge id")) {
    add("id", *p);
  } else if (auto [it, fresh] = seen.emplace(e.id, i); !fresh) {
    add("id", fmt::format("edge id {} is already used by edges[{}]", quoted_name(e.id), it->second));
  }
  const bool from_known = nodes.contains(e.from);
  const bool to_known = nodes.contains(e.to);
  if (!from_known) add("from", fmt::format("no node named {}", quoted_name(e.from)));
  if (!to_known) add("to", fmt::format("no node named {}", quoted_name(e.to)));
  if (from_known && to_known && e.from == e.to) {
    add("to",
        fmt::format("the edge leads from node {} back to itself (self-loops are not allowed)", quoted_name(e.from)));
  }
  if (auto p = name_problem(e.action, "the action")) add("action", *p);
  if (e.top_speed && (!std::isfinite(*e.top_speed) || *e.top_speed <= 0)) {
    add("top_speed", fmt::format("must be a finite speed above 0 m/s, not {}", *e.top_speed));
  }
  if (e.door) {
    if (auto p = name_problem(*e.door, "a door id")) add("door", *p);
  }
}

// The nodes reachable from `start` following edges forwards (or backwards).
std::vector<bool> reachable(const TopoMap& map, const std::vector<NodeIndex>& start, bool forwards) {
  std::vector<bool> seen(map.node_count(), false);
  std::vector<NodeIndex> todo = start;
  for (NodeIndex n : start) seen[n] = true;
  while (!todo.empty()) {
    const NodeIndex n = todo.back();
    todo.pop_back();
    for (EdgeIndex e : forwards ? map.out_edges(n) : map.in_edges(n)) {
      const NodeIndex next = forwards ? map.to_index(e) : map.from_index(e);
      if (!seen[next]) {
        seen[next] = true;
        todo.push_back(next);
      }
    }
  }
  return seen;
}

// The passages whose edges carry different narrow marks (one direction marked, the other not, or
// marked otherwise): one sentence per pair of nodes, at its first edge.
void narrow_mismatch_warnings(const TopoMap& map, std::vector<std::string>& out) {
  for (EdgeIndex e = 0; e < map.edge_count(); ++e) {
    const NodeIndex a = map.from_index(e), b = map.to_index(e);
    std::optional<EdgeIndex> other;  // another edge of the passage, marked otherwise
    bool earlier = false;            // the passage was looked at already, at a lower edge
    for (NodeIndex from : {a, b}) {
      for (EdgeIndex o : map.out_edges(from)) {
        if (map.to_index(o) != (from == a ? b : a)) continue;
        earlier = earlier || o < e;
        if (!other && map.edge(o).narrow != map.edge(e).narrow) other = o;
      }
    }
    if (earlier || !other) continue;
    out.push_back(
        fmt::format("edges {} (narrow: {}) and {} (narrow: {}) lead between the same two nodes: the "
                    "simulator takes the passage as {}",
                    quoted_name(map.edge(e).id), to_string(map.edge(e).narrow), quoted_name(map.edge(*other).id),
                    to_string(map.edge(*other).narrow), to_string(passage_narrow(map, e))));
  }
}

}  // namespace

std::vector<MapProblem> find_map_problems(const std::vector<Node>& nodes, const std::vector<Edge>& edges) {
  std::vector<MapProblem> out;
  std::unordered_map<std::string_view, std::size_t> node_names;
  for (std::size_t i = 0; i < nodes.size(); ++i) check_node(nodes, i, node_names, out);
  std::unordered_map<std::string_view, std::size_t> edge_ids;
  for (std::size_t i = 0; i < edges.size(); ++i) check_edge(edges, i, node_names, edge_ids, out);
  return out;
}

std::string describe(const MapProblem& p, const std::vector<Node>& nodes, const std::vector<Edge>& edges) {
  std::string where;
  if (p.subject == MapProblem::Subject::kNode) {
    where = fmt::format("nodes[{}]", p.index);
    if (p.index < nodes.size() && !nodes[p.index].name.empty()) where += " " + quoted_name(nodes[p.index].name);
  } else {
    where = fmt::format("edges[{}]", p.index);
    if (p.index < edges.size() && !edges[p.index].id.empty()) where += " " + quoted_name(edges[p.index].id);
  }
  return where + ": " + (p.field.empty() ? "" : p.field + ": ") + p.message;
}

std::vector<std::vector<NodeIndex>> strongly_connected_components(const TopoMap& map) {
  // Tarjan's algorithm with an explicit call stack, so deep maps cannot overflow the real one.
  constexpr std::size_t kUnvisited = static_cast<std::size_t>(-1);
  const std::size_t n = map.node_count();
  std::vector<std::size_t> index(n, kUnvisited);
  std::vector<std::size_t> low(n, 0);
  std::vector<bool> on_stack(n, false);
  std::vector<NodeIndex> stack;
  std::vector<std::pair<NodeIndex, std::size_t>> calls;  // node, position in its out-edges
  std::vector<std::vector<NodeIndex>> components;
  std::size_t counter = 0;

  auto visit = [&](NodeIndex v) {
    index[v] = low[v] = counter++;
    stack.push_back(v);
    on_stack[v] = true;
    calls.emplace_back(v, 0);
  };
  for (NodeIndex s = 0; s < n; ++s) {
    if (index[s] != kUnvisited) continue;
    visit(s);
    while (!calls.empty()) {
      const NodeIndex v = calls.back().first;
      const auto outs = map.out_edges(v);
      if (calls.back().second < outs.size()) {
        const NodeIndex w = map.to_index(outs[calls.back().second++]);
        if (index[w] == kUnvisited) {
          visit(w);
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      if (low[v] == index[v]) {
        std::vector<NodeIndex> component;
        NodeIndex w = 0;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = false;
          component.push_back(w);
        } while (w != v);
        std::sort(component.begin(), component.end());
        components.push_back(std::move(component));
      }
      calls.pop_back();
      if (!calls.empty()) {
        const NodeIndex u = calls.back().first;
        low[u] = std::min(low[u], low[v]);
      }
    }
  }
  std::sort(components.begin(), components.end(), [](const auto& a, const auto& b) {
    return a.size() != b.size() ? a.size() > b.size() : a.front() < b.front();
  });
  return components;
}

namespace {

// The map is not strongly connected: the groups, and each node outside the largest.
void connectivity_warnings(const TopoMap& map, std::vector<std::string>& out) {
  const auto components = strongly_connected_components(map);
  if (components.size() <= 1) return;
  const std::vector<NodeIndex>& main = components.front();
  out.push_back(
      fmt::format("the map is not strongly connected: {} groups of nodes; the largest holds {} of the {} nodes "
                  "(around {}), and the robot cannot go back and forth between it and the others",
                  components.size(), main.size(), map.node_count(), quoted_name(map.node(main.front()).name)));
  const std::vector<bool> from_main = reachable(map, main, true);
  const std::vector<bool> to_main = reachable(map, main, false);
  std::vector<bool> in_main(map.node_count(), false);
  for (NodeIndex i : main) in_main[i] = true;
  for (NodeIndex i = 0; i < map.node_count(); ++i) {
    if (in_main[i]) continue;
    const std::string name = quoted_name(map.node(i).name);
    if (!from_main[i] && !to_main[i]) {
      out.push_back(fmt::format("node {} is cut off: no path leads between it and the largest group", name));
    } else if (!from_main[i]) {
      out.push_back(fmt::format("node {} cannot be reached from the largest group of nodes", name));
    } else {
      out.push_back(fmt::format("node {} is a dead end: the robot cannot get back from it to the largest group", name));
    }
  }
}

}  // namespace

std::vector<std::string> map_warnings(const TopoMap& map) {
  std::vector<std::string> out;
  connectivity_warnings(map, out);
  narrow_mismatch_warnings(map, out);
  return out;
}

}  // namespace rondo::map
