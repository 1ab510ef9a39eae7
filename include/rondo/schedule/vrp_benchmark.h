// Readers of the vehicle routing benchmarks as FleetProblems, and the writer of their solution
// format, for `rondo schedule --vrptw` / `--pdptw` and bench/:
// - VRPTW, the Solomon / Gehring-Homberger text format: a name line, a VEHICLE section (NUMBER,
//   CAPACITY), a CUSTOMER section of rows "id x y demand ready due service"; row 0 is the depot;
// - PDPTW, the Li & Lim format: "vehicles capacity speed" (speed unused: travel time = distance,
//   as in every published result; some files hold 0), then rows
//   "id x y demand ready due service pickup delivery" (a pickup names its delivery's id, a
//   delivery its pickup's); row 0 is the depot.
// Robots are the vehicles, alike, from the depot at its ready time and back by its due time;
// customers are tasks whose window bounds the start; travel time = Euclidean distance, unrounded
// (double), one file unit = kVrpUnit; the objective is kVehiclesThenDistance.
//
//   Result<FleetProblem> p = load_vrptw("/work/data-vrptw/solomon/R101.txt");
//   // error: "R101.txt:12: customer row: expected 7 numbers, found 6"
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_problem.h"

namespace rondo::schedule {

// One time unit of the files in rondo time. Travel is rounded up to the millisecond, i.e. to
// 1e-6 file units, so a plan feasible here is feasible in exact arithmetic too.
inline constexpr Duration kVrpUnit = std::chrono::seconds(1000);

Result<FleetProblem> parse_vrptw(std::string_view text, const std::string& source);
Result<FleetProblem> load_vrptw(const std::filesystem::path& file);
Result<FleetProblem> parse_pdptw(std::string_view text, const std::string& source);
Result<FleetProblem> load_pdptw(const std::filesystem::path& file);

// "Route 1: 5 3 7", one line per robot that has tasks, numbered from 1, task ids in order.
std::string format_routes(const FleetProblem& problem, const FleetPlan& plan);

}  // namespace rondo::schedule
