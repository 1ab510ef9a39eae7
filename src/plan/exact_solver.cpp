#include "rondo/plan/exact_solver.h"

#include <utility>

#include <fmt/format.h>

namespace rondo::plan {
namespace {

constexpr std::uint32_t kAbsent = 0xffffffffu;
constexpr std::uint32_t kSettled = 0xfffffffeu;
constexpr std::size_t kArity = 4;

// The heap operations over (heap, position, cost); the smallest cost at heap[0].
struct Heap {
  std::vector<NodeIndex>& heap;
  std::vector<std::uint32_t>& position;
  const std::vector<double>& cost;

  void place(std::size_t at, NodeIndex node) {
    heap[at] = node;
    position[node] = static_cast<std::uint32_t>(at);
  }
  void sift_up(std::size_t at) {
    const NodeIndex node = heap[at];
    const double c = cost[node];
    while (at > 0) {
      const std::size_t parent = (at - 1) / kArity;
      if (!(c < cost[heap[parent]])) break;
      place(at, heap[parent]);
      at = parent;
    }
    place(at, node);
  }
  void sift_down(std::size_t at) {
    const NodeIndex node = heap[at];
    const double c = cost[node];
    const std::size_t n = heap.size();
    for (;;) {
      const std::size_t first = at * kArity + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t last = std::min(first + kArity, n);
      for (std::size_t k = first + 1; k < last; ++k)
        if (cost[heap[k]] < cost[heap[best]]) best = k;
      if (!(cost[heap[best]] < c)) break;
      place(at, heap[best]);
      at = best;
    }
    place(at, node);
  }
  // Inserts `node` or moves it up after its cost fell.
  void push_or_decrease(NodeIndex node) {
    if (position[node] == kAbsent) {
      heap.push_back(node);
      position[node] = static_cast<std::uint32_t>(heap.size() - 1);
    }
    sift_up(position[node]);
  }
  NodeIndex pop() {
    const NodeIndex top = heap[0];
    position[top] = kSettled;
    const NodeIndex last = heap.back();
    heap.pop_back();
    if (!heap.empty()) {
      heap[0] = last;
      sift_down(0);
    }
    return top;
  }
};

}  // namespace

Result<Solution> ExactSolver::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));

  std::vector<double> cost(n, kInfinity);
  std::vector<PolicyStep> steps(n, PolicyStep{.edge = Policy::kNoEdge});
  position_.assign(n, kAbsent);
  heap_.clear();
  Heap heap{heap_, position_, cost};
  cost[target] = 0.0;
  heap.push_or_decrease(target);
  // Reverse Dijkstra on the crossing costs τ/p (never NaN): cost[v] is final when v is popped.
  while (!heap_.empty()) {
    const NodeIndex v = heap.pop();
    const double d = cost[v];
    for (const Mdp::InArc& arc : mdp.usable_in(v)) {
      const NodeIndex u = arc.from;
      const double candidate = d + arc.crossing_seconds;
      if (candidate < cost[u] && position_[u] != kSettled) {
        cost[u] = candidate;
        steps[u].from = u;
        steps[u].edge = arc.edge;
        steps[u].to = v;
        heap.push_or_decrease(u);
      }
    }
  }
  // The chosen edges' outcomes, once per node rather than once per improvement.
  for (PolicyStep& s : steps) {
    if (s.edge == Policy::kNoEdge) continue;
    const EdgeOutcome& o = mdp.outcome(s.edge);
    s.success_probability = o.success_probability;
    s.attempt_seconds = o.expected_seconds;
  }
  return Solution{
      .status = SolveStatus::kExact, .policy = Policy(target, std::move(steps), std::move(cost)), .sweeps = 0};
}

}  // namespace rondo::plan
