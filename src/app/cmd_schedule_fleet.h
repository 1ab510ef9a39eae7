// `rondo schedule --vrptw` / `--pdptw`: the fleet scheduler on the routing benchmarks
// (docs/scheduling.md, "The fleet scheduler").
#pragma once

#include <cstdint>
#include <string>

#include "commands.h"

namespace rondo::app {

struct FleetBenchmarkOptions {
  std::string vrptw;   // Solomon / Gehring-Homberger file
  std::string pdptw;   // Li & Lim file
  std::string output;  // the routes, "Route 1: 5 3 7"
  double time_limit = 10;
  std::int64_t seed = 1;
  bool json = false;
};

// Exit codes: 0 every customer served, 1 some dropped, 2 bad input.
void run_fleet_benchmark(const FleetBenchmarkOptions& options, CommandContext& ctx);

}  // namespace rondo::app
