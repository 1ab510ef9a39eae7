#include "rondo/map/topo_map.h"

#include <fmt/format.h>

#include "rondo/map/map_validation.h"
#include "rondo/core/utf8.h"

namespace rondo::map {
namespace {

// Compressed adjacency: `start[i] .. start[i+1]` indexes the edges of node i in `out`, in edge order.
void build_adjacency(std::size_t node_count, const std::vector<std::pair<NodeIndex, NodeIndex>>& ends, bool by_source,
                     std::vector<std::size_t>& start, std::vector<EdgeIndex>& out) {
  start.assign(node_count + 1, 0);
  for (const auto& [from, to] : ends) ++start[(by_source ? from : to) + 1];
  for (std::size_t i = 0; i < node_count; ++i) start[i + 1] += start[i];
  out.assign(ends.size(), 0);
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (EdgeIndex e = 0; e < ends.size(); ++e) {
    const NodeIndex n = by_source ? ends[e].first : ends[e].second;
    out[next[n]++] = e;
  }
}

}  // namespace

const char* to_string(Narrow narrow) {
  switch (narrow) {
    case Narrow::kNone:
      return "none";
    case Narrow::kSingle:
      return "single";
    case Narrow::kOneWay:
      return "one_way";
  }
  return "none";
}

std::optional<Narrow> narrow_from_string(std::string_view word) {
  if (word == "single") return Narrow::kSingle;
  if (word == "one_way") return Narrow::kOneWay;
  return std::nullopt;
}

Result<TopoMap> TopoMap::build(std::string name, std::vector<Node> nodes, std::vector<Edge> edges) {
  const std::vector<MapProblem> problems = find_map_problems(nodes, edges);
  if (!problems.empty()) {
    std::string message = describe(problems.front(), nodes, edges);
    if (problems.size() > 1) message += fmt::format(" (and {} more problems)", problems.size() - 1);
    return Error::invalid(std::move(message));
  }
  if (first_invalid_utf8(name)) return Error::invalid("the map name must be UTF-8 text");
  TopoMap map;
  map.name_ = std::move(name);
  map.nodes_ = std::move(nodes);
  map.edges_ = std::move(edges);
  map.node_index_.reserve(map.nodes_.size());
  for (NodeIndex i = 0; i < map.nodes_.size(); ++i) map.node_index_.emplace(map.nodes_[i].name, i);
  map.edge_index_.reserve(map.edges_.size());
  map.edge_ends_.reserve(map.edges_.size());
  for (EdgeIndex e = 0; e < map.edges_.size(); ++e) {
    const Edge& edge = map.edges_[e];
    map.edge_index_.emplace(edge.id, e);
    // Both ends exist: find_map_problems checked it.
    map.edge_ends_.emplace_back(map.node_index_.find(edge.from)->second, map.node_index_.find(edge.to)->second);
  }
  build_adjacency(map.nodes_.size(), map.edge_ends_, true, map.out_start_, map.out_);
  build_adjacency(map.nodes_.size(), map.edge_ends_, false, map.in_start_, map.in_);
  return map;
}

std::optional<NodeIndex> TopoMap::find_node(std::string_view name) const {
  auto it = node_index_.find(name);
  if (it == node_index_.end()) return std::nullopt;
  return it->second;
}

std::optional<EdgeIndex> TopoMap::find_edge(std::string_view id) const {
  auto it = edge_index_.find(id);
  if (it == edge_index_.end()) return std::nullopt;
  return it->second;
}

std::span<const EdgeIndex> TopoMap::out_edges(NodeIndex i) const {
  if (i >= nodes_.size()) throw std::out_of_range(fmt::format("out_edges: no node {}", i));
  return std::span<const EdgeIndex>(out_).subspan(out_start_[i], out_start_[i + 1] - out_start_[i]);
}

std::span<const EdgeIndex> TopoMap::in_edges(NodeIndex i) const {
  if (i >= nodes_.size()) throw std::out_of_range(fmt::format("in_edges: no node {}", i));
  return std::span<const EdgeIndex>(in_).subspan(in_start_[i], in_start_[i + 1] - in_start_[i]);
}

Narrow passage_narrow(const TopoMap& map, EdgeIndex e) {
  const NodeIndex a = map.from_index(e), b = map.to_index(e);
  Narrow strictest = Narrow::kNone;
  for (NodeIndex from : {a, b}) {
    for (EdgeIndex o : map.out_edges(from)) {
      if (map.to_index(o) != (from == a ? b : a)) continue;
      const Narrow mark = map.edge(o).narrow;
      if (mark == Narrow::kSingle || (mark == Narrow::kOneWay && strictest == Narrow::kNone)) strictest = mark;
    }
  }
  return strictest;
}

bool TopoMap::operator==(const TopoMap& other) const {
  return name_ == other.name_ && nodes_ == other.nodes_ && edges_ == other.edges_;
}

}  // namespace rondo::map
