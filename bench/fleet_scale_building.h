// A hospital of any size for the fleet's scale benches (issue 38, "Scale, in bench/"): the
// deployment folder `rondo run` reads (deployment.yaml, map.yaml, routines.yaml, requests.yaml,
// world.yaml), made by code so that the number of robots, the wings and the tasks a day come from
// the command line. It is the fleet example's building (scripts/fleet_layout.py) drawn longer: a
// main corridor with ward wings off both sides (five corridor nodes each, a patient room behind a
// door either side of every one), five services behind doors, and docks in recesses along the
// main corridor, five robots to a dock.
//
//   write_scale_building("/tmp/b", {.robots = 100, .wings = 14, .tasks_per_day = 10000});
//   // 14 wings: 30 + 14 * 15 + 5 + 20 = 265 nodes
//
// The day's work is the example's kind: 60 % routines (a round or a check at a ward corridor
// node every hour for twelve hours, starting at every hour of the day in turn) and 40 % people's
// requests from 07:00 to 21:00 (deliveries of two tasks each from the pharmacy, the stores and
// the rooms, and calls for a robot to come now). The number of tasks a day is the mean: requests
// arrive as a Poisson process.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace rondo::bench {

struct ScaleBuilding {
  int robots = 100;
  int wings = 14;             // ward wings off the main corridor (at least 1)
  int tasks_per_day = 10000;  // the mean over routines and requests
  int days = 7;
  std::uint64_t seed = 1;
  std::string allocator = "fleet";  // fleet or greedy
  double routine_share = 0.6;       // of the tasks a day
};

// The node names of the building, for the benches that add tasks of their own.
inline std::string wing_node(int wing, int k) {
  return fmt::format("W{}-{}", wing, k);
}
inline std::string room_node(int wing, int k, char side) {
  return fmt::format("W{}-{}{}", wing, k, side);
}

namespace detail {

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
}

inline int main_nodes(const ScaleBuilding& b) {
  return 2 * b.wings + 2;
}
inline int docks(const ScaleBuilding& b) {
  return (b.robots + 4) / 5;
}

inline std::string map_yaml(const ScaleBuilding& b) {
  std::vector<std::string> nodes, edges;
  const auto node = [&](const std::string& name, double x, double y) {
    nodes.push_back(fmt::format("  - {{name: {}, pose: {{x: {:.1f}, y: {:.1f}}}}}", name, x, y));
  };
  const auto both = [&](const std::string& a, const std::string& z, const std::string& extra,
                        const std::string& back_extra) {
    edges.push_back(fmt::format("  - {{from: {}, to: {}{}}}", a, z, extra));
    edges.push_back(fmt::format("  - {{from: {}, to: {}{}}}", z, a, back_extra));
  };
  const int main = main_nodes(b);
  const auto main_name = [](int i) { return fmt::format("Main-{:02d}", i); };
  for (int i = 0; i < main; ++i) node(main_name(i), i * 8.0, 0.0);
  for (int i = 0; i + 1 < main; ++i) both(main_name(i), main_name(i + 1), "", "");
  // Wing w leaves main node 2w - 1, to the north for odd w and to the south for even w.
  for (int w = 1; w <= b.wings; ++w) {
    const int at = 2 * w - 1;
    const double side = w % 2 == 1 ? 1.0 : -1.0, x = at * 8.0;
    std::string prev = main_name(at);
    for (int k = 1; k <= 5; ++k) {
      const double y = side * (3.0 + (k - 1) * 6.0);
      node(wing_node(w, k), x, y);
      both(prev, wing_node(w, k), "", "");
      prev = wing_node(w, k);
      for (const char tag : {'E', 'W'}) {
        const std::string room = room_node(w, k, tag);
        node(room, x + (tag == 'E' ? 4.0 : -4.0), y);
        const std::string door = fmt::format(", action: doorPassing, door: {}-door, top_speed: 0.3", room);
        both(wing_node(w, k), room, door, door);
      }
    }
  }
  const char* services[] = {"Pharmacy", "Laboratory", "Kitchen", "Stores", "Reception"};
  for (int s = 0; s < 5; ++s) {
    // Spread along the main corridor, on its even nodes (wings leave from odd ones).
    const int at = std::min(main - 1, 2 * (s * (main / 10)));
    node(services[s], at * 8.0 + 2.0, -4.0);
    const std::string door = fmt::format(", action: doorPassing, door: {}-door, top_speed: 0.3", services[s]);
    both(main_name(at), services[s], door, door);
  }
  for (int d = 1; d <= docks(b); ++d) {
    const int at = (2 * (d - 1)) % main;
    const std::string dock = fmt::format("Dock-{}", d);
    node(dock, at * 8.0 + 2.0, 1.6 + 0.5 * ((2 * (d - 1)) / main));
    both(main_name(at), dock, ", action: docking, top_speed: 0.1", ", action: undocking, top_speed: 0.1");
  }
  std::string out = fmt::format(
      "# A hospital for the fleet's scale benches (bench/fleet_scale_building.h): {} nodes, {} edges.\n"
      "rondo_map: 1\nname: scale hospital\nnodes:\n",
      nodes.size(), edges.size());
  for (const std::string& n : nodes) out += n + "\n";
  out += "edges:\n";
  for (const std::string& e : edges) out += e + "\n";
  return out;
}

// Routines: each at one ward corridor node, every hour for twelve hours from its first hour; the
// first hours go round the day, so that work comes at every hour.
inline std::string routines_yaml(const ScaleBuilding& b) {
  const int per_routine = 12;
  const int count = std::max(1, static_cast<int>(std::lround(b.routine_share * b.tasks_per_day / per_routine)));
  std::string out = "timezone: Europe/London\nroutines:\n";
  for (int i = 0; i < count; ++i) {
    const int wing = 1 + i % b.wings, k = 1 + (i / b.wings) % 5;
    const int from = i % 13;  // 00:00 .. 12:00, so the window ends by 24:00
    const bool round = (i / 7) % 2 == 0;
    out += fmt::format(
        "  - name: r{}\n"
        "    task: {{activity: {} on ward {}, duration: {}m, priority: {}, start_node: {}, actions: [{}]}}\n"
        "    window: {{from: \"{:02d}:00\", to: \"{:02d}:00\"}}\n"
        "    every: 1h\n",
        i, round ? "vitals round" : "check", wing, round ? 4 : 2, round ? 3 : 2, wing_node(wing, k),
        round ? "vitals_round" : "room_check", from, from + per_routine);
  }
  return out;
}

inline std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return "[" + s + "]";
}

// Requests: 1.8 tasks each on average (the weights below), so that they make up the rest.
inline std::string requests_yaml(const ScaleBuilding& b) {
  std::vector<std::string> rooms, halls, first_halls, second_halls;
  for (int w = 1; w <= b.wings; ++w) {
    for (int k = 1; k <= 5; ++k) {
      halls.push_back(wing_node(w, k));
      for (const char tag : {'E', 'W'}) rooms.push_back(room_node(w, k, tag));
    }
    first_halls.push_back(wing_node(w, 1));
    second_halls.push_back(wing_node(w, 2));
  }
  std::vector<std::string> sample_rooms;
  for (std::size_t i = 0; i < rooms.size(); i += 3) sample_rooms.push_back(rooms[i]);
  second_halls.push_back("Reception");
  const double per_day = (1.0 - b.routine_share) * b.tasks_per_day / 1.8;
  return fmt::format(
      "id_prefix: call\nfrom: \"07:00\"\nto: \"21:00\"\nper_day: {:.0f}\ntemplates:\n"
      "  - {{name: medicine, weight: 4, places: [Pharmacy], duration: 1m, priority: 4,\n"
      "     deliver: {{to: {}, objects: [medicine box, infusion bag], within: 90m}}}}\n"
      "  - {{name: sample, weight: 2, places: {}, duration: 1m, priority: 4,\n"
      "     deliver: {{to: [Laboratory], objects: [sample tube], within: 90m}}}}\n"
      "  - {{name: supplies, weight: 2, places: [Stores], duration: 1m, priority: 3,\n"
      "     deliver: {{to: {}, objects: [linen, dressings], within: 2h}}}}\n"
      "  - {{name: come, weight: 2, places: {}, activity: come to the ward, duration: 5m, priority: 5,\n"
      "     actions: [visit]}}\n",
      std::max(1.0, per_day), list(rooms), list(sample_rooms), list(first_halls), list(second_halls));
}

// The fleet example's world (examples/fleet/world.yaml) without the effects that name its nodes.
inline std::string world_yaml() {
  return R"(kind: parametric
speed: 0.7
failure_probability: 0.01
noise: {sigma: 0.15, tail_probability: 0.02, tail_alpha: 1.5, tail_max: 6}
failed_duration: {min_factor: 0.3, max_factor: 1.5}
bursts: {mean_normal: 48h, mean_blocked: 10m, failure_probability: 0.6, duration_factor: 1.5}
effects:
  - {name: patient room doors shut at night, actions: [doorPassing], when: {from: "22:00", to: "07:00"}, closed: true}
  - {name: room doors shut for a while by day, actions: [doorPassing], when: {from: "07:00", to: "22:00"},
     spells: {mean_open: 4h, mean_shut: 20m}}
  - {name: any door shut for a moment, actions: [doorPassing], failure_probability: 0.04}
actions:
  default: {sigma: 0.15, failure_probability: 0.02, overrun_probability: 0.03, overrun_factor: 2.0}
  room_check: {sigma: 0.2, failure_probability: 0.02}
  vitals_round: {sigma: 0.25, failure_probability: 0.02, overrun_probability: 0.05, overrun_factor: 1.8}
  load: {sigma: 0.5, failure_probability: 0.03, overrun_probability: 0.1, overrun_factor: 2.5, non_interruptible: 30s}
  unload: {sigma: 0.5, failure_probability: 0.03, overrun_probability: 0.1, overrun_factor: 2.5, non_interruptible: 30s}
  visit: {sigma: 0.3, failure_probability: 0.01, overrun_probability: 0.1, overrun_factor: 2.0}
confirmation: {actions: [load, unload], default: 1m, places: {Pharmacy: 90s, Laboratory: 45s}}
battery: {initial: 1.0, moving_per_hour: 0.20, acting_per_hour: 0.10, idle_per_hour: 0.01, charging_per_hour: 0.50}
)";
}

inline std::string deployment_yaml(const ScaleBuilding& b) {
  std::string out = fmt::format(
      "# Written by bench/fleet_scale_building.h: {} robots, {} wings, {} tasks a day.\n"
      "rondo_deployment: 1\nname: scale hospital\nmap: map.yaml\ntime_zone: Europe/London\n"
      "dock: Dock-1\nstart: 2026-11-23\ndays: {}\nseed: {}\nroutines: routines.yaml\nworld: world.yaml\n"
      "requests: requests.yaml\nallocator: {}\n"
      "executor: {{dock_when_waiting_over: 15m, refit_at: \"02:00\"}}\ndocks:\n",
      b.robots, b.wings, b.tasks_per_day, b.days, b.seed, b.allocator);
  for (int d = 1; d <= docks(b); ++d) out += fmt::format("  - {{node: Dock-{}, capacity: 5}}\n", d);
  out += "robots:\n";
  for (int r = 0; r < b.robots; ++r)
    out += fmt::format(
        "  - {{name: r{}, dock: Dock-{}, actions: [vitals_round, room_check, visit, load, unload], capacity: 2}}\n",
        r + 1, 1 + r / 5);
  return out;
}

}  // namespace detail

// Writes the deployment into `folder` (made if missing); returns its deployment.yaml.
inline std::filesystem::path write_scale_building(const std::filesystem::path& folder, const ScaleBuilding& b) {
  std::filesystem::create_directories(folder);
  detail::write_text(folder / "map.yaml", detail::map_yaml(b));
  detail::write_text(folder / "routines.yaml", detail::routines_yaml(b));
  detail::write_text(folder / "requests.yaml", detail::requests_yaml(b));
  detail::write_text(folder / "world.yaml", detail::world_yaml());
  detail::write_text(folder / "deployment.yaml", detail::deployment_yaml(b));
  return folder / "deployment.yaml";
}

}  // namespace rondo::bench
