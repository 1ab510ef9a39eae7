// Shared pieces of the traffic tests: small maps with capacities and narrow passages, an exact
// world (no noise: an edge of 10 m takes 10 s), and a listener that keeps each robot's attempts.
#pragma once

#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/parametric_world.h"
#include "rondo/sim/sim_world.h"
#include "sim_test_util.h"

namespace rondo::sim::testing {

struct Place {
  std::string name;
  double x = 0;
  double y = 0;
  int capacity = 1;
};

// Both directions of each passage (from, to, mark), with ids "<from>_<to>".
inline map::TopoMap traffic_map(const std::vector<Place>& places,
                                const std::vector<std::tuple<std::string, std::string, map::Narrow>>& passages) {
  std::vector<map::Node> nodes;
  for (const Place& p : places) nodes.push_back({.name = p.name, .pose = {p.x, p.y, 0}, .capacity = p.capacity});
  std::vector<map::Edge> edges;
  for (const auto& [a, b, mark] : passages) {
    edges.push_back({.id = a + "_" + b, .from = a, .to = b, .action = "move_base", .narrow = mark});
    edges.push_back({.id = b + "_" + a, .from = b, .to = a, .action = "move_base", .narrow = mark});
  }
  return map::TopoMap::build("traffic", std::move(nodes), std::move(edges)).value();
}

// 1 m/s, no noise, no failures but on `closed` edges, whose attempts fail after half their time.
inline SimWorld exact_traffic_world(const map::TopoMap& m, std::vector<map::EdgeIndex> closed = {},
                                    double failure_probability = 0.0, double sigma = 0.0) {
  ParametricSpec spec;
  spec.default_speed = 1.0;
  spec.failure_probability = failure_probability;
  spec.noise = {.sigma = sigma, .tail_probability = 0};
  spec.failed = {.min_factor = 0.5, .max_factor = 0.5};
  if (!closed.empty()) spec.effects.push_back({.name = "closed", .edges = std::move(closed), .closed = true});
  SimWorld w;
  w.edges = std::make_unique<ParametricWorld>(m, london(), spec);
  w.battery = {.initial = 1.0, .moving_per_hour = 0.0};
  return w;
}

// Keeps the robot's edge attempts.
class Attempts final : public exec::RobotListener {
 public:
  void on_edge_finished(const exec::EdgeAttempt& a) override { edges.push_back(a); }
  void on_action_finished(const exec::ActionResult&) override {}
  void on_interruptible_changed(bool) override {}
  void on_observation(const exec::Observation&) override {}
  void on_fault(const exec::RobotFault&) override {}
  void on_ready() override {}
  std::vector<exec::EdgeAttempt> edges;
};

}  // namespace rondo::sim::testing
