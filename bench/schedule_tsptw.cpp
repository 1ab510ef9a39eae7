// Solves one TSPTW instance with the default scheduler and prints one JSON line: the same numbers
// as `rondo schedule --tsptw FILE --json`, without the rest of the command line (so the harness
// builds while other modules are half-done). Used by scripts/dumas_table.
//
//   build-schedule/bench/bench_schedule_tsptw ../shared/data/trptw/dumas/n20w20.001.tsptw 1.0
#include <chrono>
#include <cstdlib>
#include <iostream>

#include "bench_clock.h"
#include "rondo/core/document.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/tsptw.h"

using rondo::bench::steady_seconds;

int main(int argc, char** argv) {
  using namespace rondo::schedule;
  if (argc < 3) {
    std::cerr << "usage: bench_schedule_tsptw FILE SECONDS\n";
    return 2;
  }
  const double limit = std::atof(argv[2]);
  auto problem = load_tsptw(argv[1]);
  if (!problem) {
    std::cerr << problem.error().message << '\n';
    return 2;
  }
  const double started = steady_seconds();
  DeadlineStop stop(steady_seconds, started + limit);
  DefaultScheduler solver;
  Schedule s = solver.solve(*problem, stop);
  s.seconds = steady_seconds() - started;
  const CheckReport check = check_schedule(*problem, s);
  rondo::Json j;
  j["status"] = to_string(s.status);
  j["objective"] = tsptw_units(s.objective);
  j["seconds"] = s.seconds;
  j["checked"] = check.ok();
  j["order"] = rondo::Json::array();
  for (const auto& e : s.entries) j["order"].push_back(problem->tasks[e.task].id);
  std::cout << j.dump() << '\n';
  return check.ok() ? 0 : 1;
}
