// `rondo run`: one deployment lived on the simulated robot, day by day, writing its run folder.
//
//   RunRequest r{.deployment = *load_deployment(file), .out = "runs/x"};
//   Result<RunResult> done = run_deployment(r, std::cerr);   // progress to a terminal
//
// The run folder holds report.json (deterministic for a seed: no wall-clock figures), run.json
// (wall-clock figures of this run), days/<date>.svg (planned against actual), and rondo.sqlite
// (tasks, the event log, the traversal log).
//
// The same request on the same folder again resumes the run there, up to the same end (a run that
// was killed goes on from the latest thing its store holds); a folder holding another run is
// refused (kInvalidInput, naming what differs) and a finished one is not run again.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>

#include "deployment.h"
#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/exec/executor.h"
#include "rondo/exec/robot.h"

namespace rondo::app {

struct RunRequest {
  Deployment deployment;
  std::filesystem::path out;
  bool realtime = false;  // the system clock instead of simulated time
  double speed = 1.0;     // with realtime: the system clock this many times faster (SystemClock)
  std::optional<Duration> run_for;  // stop this long after the start (rondo's clock), before the days end
  bool progress = false;  // draw a progress bar on `progress_to`
  // Benchmarks only (bench/courier_fortnight_bench.cpp): a listener put between the robot and the
  // executor, which must forward every callback to `executor` (it may time them); kept for the run.
  std::function<std::unique_ptr<exec::RobotListener>(exec::Executor& executor)> wrap_listener{};
};

struct RunResult {
  Json report;           // what report.json holds
  bool already_finished = false;  // the folder held this run, finished: nothing ran
  bool resumed = false;           // the folder held this run, stopped before its end: it went on
  double wall_seconds = 0;
  int write_errors = 0;  // store writes that failed during the run
};

Result<RunResult> run_deployment(const RunRequest& request, std::ostream& progress_to);

}  // namespace rondo::app
