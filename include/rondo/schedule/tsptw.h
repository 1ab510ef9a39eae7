// Reads the TSPTW files of the LKH-3 distribution (the Dumas et al. instances in
// ../shared/data/trptw/dumas) as a Problem, following data/README.md exactly:
// node 1 is the depot and the robot's start at time 0; every other node is a task with zero
// duration and its window on the start time; the robot must be back at the depot by the depot's
// due time; travel is the matrix entry as given (no shortest-path repair). One file unit is one
// second, so the objective in file units is Schedule::objective in seconds.
//
//   Result<Problem> p = load_tsptw("../shared/data/trptw/dumas/n20w20.001.tsptw");
//   // error: "n20w20.001.tsptw:7: EDGE_WEIGHT_SECTION: expected 21 numbers in row 1, found 20"
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/schedule/problem.h"

namespace rondo::schedule {

// `source` names the text in error messages.
Result<Problem> parse_tsptw(std::string_view text, const std::string& source);
Result<Problem> load_tsptw(const std::filesystem::path& file);

// The file's units for a duration measured in rondo time (1 unit = 1 s).
std::int64_t tsptw_units(Duration d);

}  // namespace rondo::schedule
