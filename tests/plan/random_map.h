// Random maps and edge models for the planner's tests and benchmarks.
//
//   map::TopoMap m = random_map({.nodes = 200, .seed = 7});        // random digraph, dead ends
//   map::TopoMap b = building_map({.rows = 25, .columns = 40});     // a floor of places, doors
//   map::TopoMap c = corridor_building_map({});                     // floors, corridors, rooms
//   std::vector<EdgeCrossing> o = random_outcomes(m, {.seed = 7});   // some p = 0 edges
//   FunctionEdgeModels models = daily_models(b);                    // p, τ varying with the time of day
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan::testing {

inline std::string node_name(std::size_t i) {
  return "n" + std::to_string(i);
}

struct RandomMapOptions {
  std::size_t nodes = 20;
  std::uint64_t seed = 1;
  std::size_t max_out_degree = 4;  // each node gets 0..max out-edges to random other nodes
  double area = 100.0;             // metres: nodes are placed in [0, area]²
};

inline map::TopoMap random_map(const RandomMapOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> where(0.0, o.area);
  std::vector<map::Node> nodes;
  for (std::size_t i = 0; i < o.nodes; ++i)
    nodes.push_back({.name = node_name(i), .pose = {where(rng), where(rng), 0}});
  std::vector<map::Edge> edges;
  std::set<std::pair<std::size_t, std::size_t>> seen;
  std::uniform_int_distribution<std::size_t> degree(0, o.max_out_degree);
  std::uniform_int_distribution<std::size_t> other(0, o.nodes > 0 ? o.nodes - 1 : 0);
  for (std::size_t i = 0; i < o.nodes && o.nodes > 1; ++i) {
    const std::size_t k = degree(rng);
    for (std::size_t n = 0; n < k; ++n) {
      const std::size_t j = other(rng);
      if (j == i || !seen.emplace(i, j).second) continue;
      edges.push_back(
          {.id = node_name(i) + "_" + node_name(j), .from = node_name(i), .to = node_name(j), .action = "move_base"});
    }
  }
  return map::TopoMap::build("random", std::move(nodes), std::move(edges)).value();
}

struct BuildingMapOptions {
  std::size_t rows = 25;
  std::size_t columns = 40;
  std::uint64_t seed = 1;
  double spacing = 3.0;         // metres between neighbouring places
  double wall_fraction = 0.03;  // of neighbour pairs left unconnected
  double door_fraction = 0.15;  // of connections that pass a door
};

// A floor of rows × columns places, each connected both ways to its grid neighbours except across
// a few walls; some connections are doors. 1,000 places give about 3,800 directed edges.
inline map::TopoMap building_map(const BuildingMapOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<map::Node> nodes;
  auto index = [&](std::size_t r, std::size_t c) { return r * o.columns + c; };
  for (std::size_t r = 0; r < o.rows; ++r)
    for (std::size_t c = 0; c < o.columns; ++c)
      nodes.push_back({.name = node_name(index(r, c)),
                       .pose = {static_cast<double>(c) * o.spacing, static_cast<double>(r) * o.spacing, 0}});
  std::vector<map::Edge> edges;
  auto connect = [&](std::size_t a, std::size_t b) {
    if (unit(rng) < o.wall_fraction) return;
    const bool door = unit(rng) < o.door_fraction;
    const std::string action = door ? "doorPassing" : "move_base";
    std::optional<std::string> door_id;
    if (door) door_id = "d" + std::to_string(a) + "_" + std::to_string(b);
    edges.push_back({.id = node_name(a) + "_" + node_name(b),
                     .from = node_name(a),
                     .to = node_name(b),
                     .action = action,
                     .door = door_id});
    edges.push_back({.id = node_name(b) + "_" + node_name(a),
                     .from = node_name(b),
                     .to = node_name(a),
                     .action = action,
                     .door = door_id});
  };
  for (std::size_t r = 0; r < o.rows; ++r)
    for (std::size_t c = 0; c < o.columns; ++c) {
      if (c + 1 < o.columns) connect(index(r, c), index(r, c + 1));
      if (r + 1 < o.rows) connect(index(r, c), index(r + 1, c));
    }
  return map::TopoMap::build("building", std::move(nodes), std::move(edges)).value();
}

struct CorridorBuildingOptions {
  std::size_t floors = 4;
  std::size_t corridor_nodes = 34;  // per floor, `spacing` apart
  std::size_t rooms_per_side = 18;  // per floor and side of the corridor
  std::size_t room_rows = 2;        // places per room: rows × columns, meshed with diagonals
  std::size_t room_columns = 3;
  double spacing = 2.5;             // metres
  double floor_offset = 20.0;       // metres between floors in y: the lift edge's length
};

// A building as real topological maps of long-term deployments look (STRANDS' g4s, aaf and tsc
// maps have a hop diameter of about a third of their node count): on every floor one long
// corridor with rooms off both sides, each room a small mesh of places (with diagonals, as open
// areas are mapped) behind a door; a lift joins the corridor's first places of consecutive
// floors. Defaults: 4 floors × (34 + 36 rooms × 6) = 1,000 places and 3,726 directed edges, hop
// diameter 73 (the lift is at one end of each corridor).
inline map::TopoMap corridor_building_map(const CorridorBuildingOptions& o) {
  std::vector<map::Node> nodes;
  std::vector<map::Edge> edges;
  auto add_node = [&](double x, double y) {
    nodes.push_back({.name = node_name(nodes.size()), .pose = {x, y, 0}});
    return nodes.size() - 1;
  };
  auto connect = [&](std::size_t a, std::size_t b, const std::string& action, bool door) {
    std::optional<std::string> door_id;
    if (door) door_id = "d" + std::to_string(a) + "_" + std::to_string(b);
    for (auto [u, v] : {std::pair{a, b}, std::pair{b, a}})
      edges.push_back({.id = node_name(u) + "_" + node_name(v), .from = node_name(u), .to = node_name(v),
                       .action = action, .door = door_id});
  };
  std::vector<std::size_t> lift_stops;
  for (std::size_t f = 0; f < o.floors; ++f) {
    const double y0 = static_cast<double>(f) * o.floor_offset;
    std::vector<std::size_t> corridor;
    for (std::size_t c = 0; c < o.corridor_nodes; ++c) {
      corridor.push_back(add_node(static_cast<double>(c) * o.spacing, y0));
      if (c > 0) connect(corridor[c - 1], corridor[c], "move_base", false);
    }
    lift_stops.push_back(corridor.front());
    for (int side : {-1, 1}) {
      for (std::size_t k = 0; k < o.rooms_per_side; ++k) {
        const std::size_t anchor = corridor[k * o.corridor_nodes / o.rooms_per_side];
        const double x0 = nodes[anchor].pose.x;
        std::vector<std::size_t> room;
        for (std::size_t r = 0; r < o.room_rows; ++r)
          for (std::size_t c = 0; c < o.room_columns; ++c)
            room.push_back(add_node(x0 + static_cast<double>(c) * 0.8,
                                    y0 + side * (2.0 + static_cast<double>(r) * 0.8 + 0.1 * static_cast<double>(c))));
        auto at = [&](std::size_t r, std::size_t c) { return room[r * o.room_columns + c]; };
        for (std::size_t r = 0; r < o.room_rows; ++r)
          for (std::size_t c = 0; c < o.room_columns; ++c) {
            if (c + 1 < o.room_columns) connect(at(r, c), at(r, c + 1), "move_base", false);
            if (r + 1 < o.room_rows) connect(at(r, c), at(r + 1, c), "move_base", false);
            if (r + 1 < o.room_rows && c + 1 < o.room_columns) {
              connect(at(r, c), at(r + 1, c + 1), "move_base", false);
              connect(at(r, c + 1), at(r + 1, c), "move_base", false);
            }
          }
        connect(anchor, at(0, 0), "doorPassing", true);
      }
    }
  }
  for (std::size_t f = 1; f < lift_stops.size(); ++f) connect(lift_stops[f - 1], lift_stops[f], "lift", false);
  return map::TopoMap::build("corridor_building", std::move(nodes), std::move(edges)).value();
}

// The largest number of edges on a fewest-edges path between two nodes (breadth-first search
// from every node): what bounds value iteration's sweeps from below.
inline std::size_t hop_diameter(const map::TopoMap& m) {
  std::size_t best = 0;
  std::vector<std::size_t> depth(m.node_count());
  std::vector<map::NodeIndex> queue;
  for (map::NodeIndex s = 0; s < m.node_count(); ++s) {
    std::fill(depth.begin(), depth.end(), static_cast<std::size_t>(-1));
    queue.assign(1, s);
    depth[s] = 0;
    for (std::size_t k = 0; k < queue.size(); ++k) {
      const map::NodeIndex v = queue[k];
      best = std::max(best, depth[v]);
      for (map::EdgeIndex e : m.out_edges(v)) {
        const map::NodeIndex w = m.to_index(e);
        if (depth[w] == static_cast<std::size_t>(-1)) {
          depth[w] = depth[v] + 1;
          queue.push_back(w);
        }
      }
    }
  }
  return best;
}

struct RandomOutcomeOptions {
  std::uint64_t seed = 1;
  double closed_fraction = 0.05;  // edges with p = 0
  double min_probability = 0.2;   // the others: p uniform in [min, 1]
  double min_seconds = 1.0;       // τ uniform in [min, max]
  double max_seconds = 60.0;
};

inline std::vector<EdgeCrossing> random_outcomes(const map::TopoMap& m, const RandomOutcomeOptions& o) {
  std::mt19937_64 rng(o.seed ^ 0x9e3779b97f4a7c15ULL);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<EdgeCrossing> out;
  for (std::size_t e = 0; e < m.edge_count(); ++e) {
    const bool closed = unit(rng) < o.closed_fraction;
    const double p = closed ? 0.0 : o.min_probability + (1.0 - o.min_probability) * unit(rng);
    out.push_back(
        {.success_probability = p, .expected_seconds = o.min_seconds + (o.max_seconds - o.min_seconds) * unit(rng)});
  }
  return out;
}

// Models with a daily rhythm: edges are slower and doors fail more often around midday, and each
// edge has its own phase. Deterministic in (edge, time); version 0.
inline FunctionEdgeModels daily_models(const map::TopoMap& m, double seconds_per_metre = 2.0) {
  std::vector<double> base;
  std::vector<bool> door;
  for (std::size_t e = 0; e < m.edge_count(); ++e) {
    const auto& a = m.node(m.from_index(e)).pose;
    const auto& b = m.node(m.to_index(e)).pose;
    base.push_back(std::hypot(a.x - b.x, a.y - b.y) * seconds_per_metre + 1.0);
    door.push_back(m.edge(e).door.has_value());
  }
  return FunctionEdgeModels([base, door](map::EdgeIndex e, Time t) {
    constexpr double kDay = 86400.0;
    const double day_fraction = std::fmod(to_unix_seconds(t), kDay) / kDay;
    const double phase = static_cast<double>(e % 7) / 7.0;
    const double wave = 0.5 * (1.0 + std::sin(2.0 * M_PI * (day_fraction + phase)));  // in [0, 1]
    const double p = door[e] ? 0.55 + 0.4 * (1.0 - wave) : 0.9 + 0.1 * (1.0 - wave);
    return EdgeCrossing{.success_probability = p, .expected_seconds = base[e] * (1.0 + 0.5 * wave)};
  });
}

}  // namespace rondo::plan::testing
