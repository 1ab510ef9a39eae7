#include "rondo/plan/dead_ends.h"

#include <algorithm>
#include <limits>

namespace rondo::plan {

namespace {

// The map as an undirected graph in compressed rows: both ends of every edge, self-loops never
// occur (TopoMap forbids them), parallel links are harmless.
struct UndirectedGraph {
  std::vector<std::size_t> start;
  std::vector<map::NodeIndex> next;

  explicit UndirectedGraph(const map::TopoMap& m) : start(m.node_count() + 1, 0) {
    for (map::NodeIndex v = 0; v < m.node_count(); ++v) {
      start[v] = next.size();
      for (map::EdgeIndex e : m.out_edges(v)) next.push_back(m.to_index(e));
      for (map::EdgeIndex e : m.in_edges(v)) next.push_back(m.from_index(e));
    }
    start[m.node_count()] = next.size();
  }
  std::size_t degree(map::NodeIndex v) const { return start[v + 1] - start[v]; }
};

// A depth-first search forest with preorder numbers, low points and subtree sizes.
struct DepthFirstForest {
  static constexpr std::size_t kUnseen = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> preorder;   // per node: its position in `order`
  std::vector<std::size_t> low;        // the least preorder number reachable by one back link
  std::vector<std::size_t> size;       // of the node's subtree
  std::vector<map::NodeIndex> parent;  // a root is its own parent
  std::vector<map::NodeIndex> order;   // nodes in preorder: a subtree is a contiguous range

  explicit DepthFirstForest(const UndirectedGraph& g) {
    const std::size_t n = g.start.size() - 1;
    preorder.assign(n, kUnseen);
    low.assign(n, 0);
    size.assign(n, 1);
    parent.assign(n, 0);
    order.reserve(n);
    // The best connected node first: it is most likely in the core (a region cannot hold the root).
    map::NodeIndex hub = 0;
    for (map::NodeIndex v = 1; v < n; ++v) {
      if (g.degree(v) > g.degree(hub)) hub = v;
    }
    if (n > 0) search_from(g, hub);
    for (map::NodeIndex v = 0; v < n; ++v) {
      if (preorder[v] == kUnseen) search_from(g, v);
    }
  }

 private:
  void discover(map::NodeIndex v, map::NodeIndex from) {
    parent[v] = from;
    preorder[v] = low[v] = order.size();
    order.push_back(v);
  }

  // Iterative, so that long corridors cannot overflow the call stack.
  void search_from(const UndirectedGraph& g, map::NodeIndex root) {
    struct Frame {
      map::NodeIndex node;
      std::size_t next;  // position in the node's row
    };
    std::vector<Frame> stack{{root, g.start[root]}};
    discover(root, root);
    while (!stack.empty()) {
      const map::NodeIndex v = stack.back().node;
      if (stack.back().next < g.start[v + 1]) {
        const map::NodeIndex w = g.next[stack.back().next++];
        if (preorder[w] == kUnseen) {
          discover(w, v);
          stack.push_back({w, g.start[w]});
        } else {
          low[v] = std::min(low[v], preorder[w]);
        }
        continue;
      }
      stack.pop_back();
      if (!stack.empty()) {
        const map::NodeIndex p = stack.back().node;
        low[p] = std::min(low[p], low[v]);
        size[p] += size[v];
      }
    }
  }
};

}  // namespace

DeadEnds DeadEnds::find(const map::TopoMap& map, std::size_t max_region_nodes) {
  const std::size_t n = map.node_count();
  DeadEnds out;
  out.region_of_.assign(n, kCore);
  const DepthFirstForest forest{UndirectedGraph(map)};
  // The subtree of a non-root node c is a component of the graph without c's parent exactly when
  // no link from the subtree climbs above the parent (low[c] >= preorder[parent]). Walking the
  // preorder and skipping each region taken keeps only the outermost qualifying subtrees; a
  // region's door is its parent, which is outside every region taken (else the walk would have
  // skipped the region inside that one).
  for (std::size_t i = 0; i < n;) {
    const map::NodeIndex c = forest.order[i];
    const map::NodeIndex door = forest.parent[c];
    const std::size_t size = forest.size[c];
    const bool separated = door != c && forest.low[c] >= forest.preorder[door];
    if (!separated || size > max_region_nodes || 2 * size >= n) {
      ++i;
      continue;
    }
    const auto region = static_cast<std::uint32_t>(out.door_.size());
    out.door_.push_back(door);
    for (std::size_t k = i; k < i + size; ++k) {
      out.members_.push_back(forest.order[k]);
      out.region_of_[forest.order[k]] = region;
    }
    out.start_.push_back(out.members_.size());
    i += size;
  }
  return out;
}

}  // namespace rondo::plan
